// load_generator: sends EIP data datagrams (docs/protocol.md §2) to one UDP destination with
// sendmmsg, paced in batches against absolute deadlines.
//
// E exchanges (ids first..first+E-1, producer id --producer) of T tags each: tag 0 "ts" is a lint
// at offset 0 carrying CLOCK_REALTIME ns at send time (end-to-end latency), tags 1..T-1 are dints
// at 8 + 4 (i - 1). Datagram i goes to exchange i mod E, so with R = E x 1000 / period_ms every
// exchange is sent exactly once per period. Per datagram, round(change x T) tags change: "ts" (if
// stamping) and the next dints in rotation, set to the exchange's datagram count. --request-id
// starts every exchange's sequence there (a run continuing an earlier one's).
//
// Prints one JSON line: sent, errors, elapsed_s, rate.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <optional>
#include <vector>

#include "bench_common.hpp"

namespace {

constexpr std::size_t header_size = 32;
constexpr std::size_t max_batch = 1024;

struct Exchange {
    std::vector<unsigned char> bytes;  ///< header + data
    std::uint16_t request_id = 0;
    std::uint32_t count = 0;  ///< datagrams sent, the value of changed dints
    std::size_t cursor = 0;   ///< next dint to change
};

void put_u16(unsigned char* p, std::uint16_t v) { std::memcpy(p, &v, 2); }  // x86: LE
void put_u32(unsigned char* p, std::uint32_t v) { std::memcpy(p, &v, 4); }
void put_i64(unsigned char* p, std::int64_t v) { std::memcpy(p, &v, 8); }

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(
        argc, argv,
        {"host", "port", "exchanges", "first-exchange", "producer", "tags", "rate", "duration",
         "count", "change", "no-stamp", "batch-us", "final-value", "request-id"});
    const std::string host = opt.str("host", "127.0.0.1");
    const auto port = static_cast<std::uint16_t>(opt.num("port", 18246));
    const auto exchanges = static_cast<std::size_t>(opt.num("exchanges", 1));
    const auto first = static_cast<std::uint32_t>(opt.num("first-exchange", 1));
    const auto tags = static_cast<std::size_t>(std::max(1.0, opt.num("tags", 100)));
    const double rate = opt.num("rate", 1000);
    const double duration = opt.num("duration", 5);
    const double change = opt.num("change", 0.1);
    const bool stamp = !opt.has("no-stamp");
    const auto batch_ns = static_cast<std::int64_t>(opt.num("batch-us", 1000) * 1000);
    const auto total = static_cast<std::uint64_t>(opt.has("count") ? opt.num("count", 0)
                                                                   : std::llround(rate * duration));
    in_addr producer{};
    if (inet_pton(AF_INET, opt.str("producer", "10.0.0.1").c_str(), &producer) != 1) {
        bench::Options::fail("--producer is not an IPv4 address");
    }
    if (exchanges == 0 || rate <= 0) bench::Options::fail("--exchanges and --rate must be > 0");

    const std::size_t data_length = 8 + 4 * (tags - 1);
    const auto changes = static_cast<std::size_t>(std::lround(change * static_cast<double>(tags)));
    std::vector<Exchange> state(exchanges);
    for (std::size_t e = 0; e < exchanges; ++e) {
        auto& b = state[e].bytes;
        b.assign(header_size + data_length, 0);
        b[0] = 0x0D;
        b[1] = 0x01;
        std::memcpy(&b[4], &producer.s_addr, 4);  // dotted (network) order
        put_u32(&b[8], first + static_cast<std::uint32_t>(e));
        // A run that follows another on the same exchanges continues its sequence.
        state[e].request_id = static_cast<std::uint16_t>(opt.num("request-id", 0));
    }

    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(port);
    inet_pton(AF_INET, host.c_str(), &to.sin_addr);
    const int sndbuf = 4 * 1024 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
    if (connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
        bench::Options::fail(std::string("connect: ") + std::strerror(errno));
    }

    // One buffer per batch slot: the datagram is copied so a later change of the same exchange
    // within the batch does not alter an earlier datagram.
    std::vector<std::vector<unsigned char>> slots(
        max_batch, std::vector<unsigned char>(header_size + data_length));
    std::vector<iovec> iov(max_batch);
    std::vector<mmsghdr> msgs(max_batch);
    for (std::size_t i = 0; i < max_batch; ++i) {
        iov[i] = {slots[i].data(), slots[i].size()};
        msgs[i] = {};
        msgs[i].msg_hdr.msg_iov = &iov[i];
        msgs[i].msg_hdr.msg_iovlen = 1;
    }

    auto build = [&](std::uint64_t index, unsigned char* out, std::optional<std::int64_t> final) {
        auto& ex = state[index % exchanges];
        auto* b = ex.bytes.data();
        put_u16(b + 2, ex.request_id++);
        ++ex.count;
        const std::int64_t wall = bench::wall_ns();
        put_u32(b + 12, static_cast<std::uint32_t>(wall / 1000000000));
        put_u32(b + 16, static_cast<std::uint32_t>(wall % 1000000000));
        auto* data = b + header_size;
        if (final) {
            put_i64(data, *final);
            for (std::size_t t = 1; t < tags; ++t) {
                put_u32(data + 8 + 4 * (t - 1), static_cast<std::uint32_t>(*final));
            }
        } else {
            std::size_t left = changes;
            if (stamp && left > 0) {
                put_i64(data, wall);
                --left;
            }
            for (; left > 0 && tags > 1; --left) {
                put_u32(data + 8 + 4 * ex.cursor, ex.count);
                ex.cursor = (ex.cursor + 1) % (tags - 1);
            }
        }
        std::memcpy(out, b, header_size + data_length);
    };

    std::uint64_t sent = 0;
    std::uint64_t errors = 0;
    auto send_range = [&](std::uint64_t from, std::uint64_t to_index,
                          std::optional<std::int64_t> final) {
        while (from < to_index) {
            const auto n =
                static_cast<std::size_t>(std::min<std::uint64_t>(to_index - from, max_batch));
            for (std::size_t i = 0; i < n; ++i) build(from + i, slots[i].data(), final);
            std::size_t done = 0;
            while (done < n) {
                const int r = sendmmsg(fd, msgs.data() + done, static_cast<unsigned>(n - done), 0);
                if (r < 0) {
                    if (errno == EINTR) continue;
                    ++errors;  // e.g. ECONNREFUSED from an earlier ICMP: skip one datagram
                    ++done;
                    continue;
                }
                done += static_cast<std::size_t>(r);
                sent += static_cast<std::uint64_t>(r);
            }
            from += n;
        }
    };

    const std::int64_t start = bench::mono_ns();
    std::uint64_t scheduled = 0;
    for (std::int64_t batch = 1; scheduled < total; ++batch) {
        // Datagrams due by the end of this batch slot, from the absolute schedule.
        const auto due = std::min<std::uint64_t>(
            total, static_cast<std::uint64_t>(static_cast<double>(batch) *
                                              static_cast<double>(batch_ns) * rate / 1e9));
        send_range(scheduled, due, std::nullopt);
        scheduled = due;
        const std::int64_t deadline = start + batch * batch_ns;
        if (bench::mono_ns() < deadline) bench::sleep_until_mono(deadline);
    }
    const double elapsed = static_cast<double>(bench::mono_ns() - start) / 1e9;
    std::uint64_t final_sent = 0;
    if (opt.has("final-value")) {
        const auto before = sent;
        send_range(total, total + exchanges, static_cast<std::int64_t>(opt.num("final-value", 0)));
        final_sent = sent - before;
        sent = before;
    }
    std::printf(
        "{\"sent\":%llu,\"final\":%llu,\"errors\":%llu,\"elapsed_s\":%.4f,\"rate\":%.1f,"
        "\"length\":%zu,\"changes\":%zu}\n",
        static_cast<unsigned long long>(sent), static_cast<unsigned long long>(final_sent),
        static_cast<unsigned long long>(errors), elapsed, static_cast<double>(sent) / elapsed,
        data_length, changes);
    close(fd);
    return 0;
}
