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
#include <string>
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

struct Settings {
    std::string host;
    std::uint16_t port = 0;
    std::size_t exchanges = 0;
    std::uint32_t first = 0;  ///< the first exchange id
    in_addr producer{};
    std::size_t tags = 0;
    double rate = 0;
    bool stamp = true;
    std::int64_t batch_ns = 0;
    std::uint64_t total = 0;  ///< datagrams to send
    std::uint16_t request_id = 0;
    std::optional<std::int64_t> final_value;
    std::size_t data_length = 0;
    std::size_t changes = 0;  ///< tags changed per datagram
};

Settings read_settings(int argc, char** argv) {
    const bench::Options opt(
        argc, argv,
        {"host", "port", "exchanges", "first-exchange", "producer", "tags", "rate", "duration",
         "count", "change", "no-stamp", "batch-us", "final-value", "request-id"});
    Settings s;
    s.host = opt.str("host", "127.0.0.1");
    s.port = static_cast<std::uint16_t>(opt.num("port", 18246));
    s.exchanges = static_cast<std::size_t>(opt.num("exchanges", 1));
    s.first = static_cast<std::uint32_t>(opt.num("first-exchange", 1));
    s.tags = static_cast<std::size_t>(std::max(1.0, opt.num("tags", 100)));
    s.rate = opt.num("rate", 1000);
    const double duration = opt.num("duration", 5);
    s.stamp = !opt.has("no-stamp");
    s.batch_ns = static_cast<std::int64_t>(opt.num("batch-us", 1000) * 1000);
    s.total = static_cast<std::uint64_t>(opt.has("count") ? opt.num("count", 0)
                                                          : std::llround(s.rate * duration));
    if (inet_pton(AF_INET, opt.str("producer", "10.0.0.1").c_str(), &s.producer) != 1) {
        bench::Options::fail("--producer is not an IPv4 address");
    }
    if (s.exchanges == 0 || s.rate <= 0) bench::Options::fail("--exchanges and --rate must be > 0");
    // A run that follows another on the same exchanges continues its sequence.
    s.request_id = static_cast<std::uint16_t>(opt.num("request-id", 0));
    if (opt.has("final-value")) {
        s.final_value = static_cast<std::int64_t>(opt.num("final-value", 0));
    }
    s.data_length = 8 + 4 * (s.tags - 1);
    s.changes =
        static_cast<std::size_t>(std::lround(opt.num("change", 0.1) * static_cast<double>(s.tags)));
    return s;
}

int connect_socket(const Settings& s) {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in to{};
    to.sin_family = AF_INET;
    to.sin_port = htons(s.port);
    inet_pton(AF_INET, s.host.c_str(), &to.sin_addr);
    const int sndbuf = 4 * 1024 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &sndbuf, sizeof sndbuf);
    if (connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
        bench::Options::fail(std::string("connect: ") + std::strerror(errno));
    }
    return fd;
}

/// The exchanges' datagrams, built in turn and sent in batches with sendmmsg.
class Generator {
public:
    Generator(const Settings& s, int fd) : s_(s), fd_(fd), state_(s.exchanges) {
        for (std::size_t e = 0; e < s.exchanges; ++e) {
            auto& b = state_[e].bytes;
            b.assign(header_size + s.data_length, 0);
            b[0] = 0x0D;
            b[1] = 0x01;
            std::memcpy(&b[4], &s.producer.s_addr, 4);  // dotted (network) order
            put_u32(&b[8], s.first + static_cast<std::uint32_t>(e));
            state_[e].request_id = s.request_id;
        }
        // One buffer per batch slot: the datagram is copied so a later change of the same
        // exchange within the batch does not alter an earlier datagram.
        slots_.assign(max_batch, std::vector<unsigned char>(header_size + s.data_length));
        iov_.resize(max_batch);
        msgs_.resize(max_batch);
        for (std::size_t i = 0; i < max_batch; ++i) {
            iov_[i] = {slots_[i].data(), slots_[i].size()};
            msgs_[i] = {};
            msgs_[i].msg_hdr.msg_iov = &iov_[i];
            msgs_[i].msg_hdr.msg_iovlen = 1;
        }
    }

    /// Sends datagrams [from, to) of the schedule; with `final`, every tag carries that value.
    void send_range(std::uint64_t from, std::uint64_t to, std::optional<std::int64_t> final) {
        while (from < to) {
            const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(to - from, max_batch));
            for (std::size_t i = 0; i < n; ++i) build(from + i, slots_[i].data(), final);
            send_batch(n);
            from += n;
        }
    }

    /// Sends one datagram per exchange (datagrams [from, from + exchanges) of the schedule)
    /// whose every tag carries `value`; returns how many went, which sent() leaves out.
    std::uint64_t send_final(std::uint64_t from, std::int64_t value) {
        const auto before = sent_;
        send_range(from, from + s_.exchanges, value);
        const auto final_sent = sent_ - before;
        sent_ = before;
        return final_sent;
    }

    std::uint64_t sent() const { return sent_; }
    std::uint64_t errors() const { return errors_; }

private:
    void build(std::uint64_t index, unsigned char* out, std::optional<std::int64_t> final) {
        auto& ex = state_[index % s_.exchanges];
        auto* b = ex.bytes.data();
        put_u16(b + 2, ex.request_id++);
        ++ex.count;
        const std::int64_t wall = bench::wall_ns();
        put_u32(b + 12, static_cast<std::uint32_t>(wall / 1000000000));
        put_u32(b + 16, static_cast<std::uint32_t>(wall % 1000000000));
        auto* data = b + header_size;
        if (final) {
            put_i64(data, *final);
            for (std::size_t t = 1; t < s_.tags; ++t) {
                put_u32(data + 8 + 4 * (t - 1), static_cast<std::uint32_t>(*final));
            }
        } else {
            std::size_t left = s_.changes;
            if (s_.stamp && left > 0) {
                put_i64(data, wall);
                --left;
            }
            for (; left > 0 && s_.tags > 1; --left) {
                put_u32(data + 8 + 4 * ex.cursor, ex.count);
                ex.cursor = (ex.cursor + 1) % (s_.tags - 1);
            }
        }
        std::memcpy(out, b, header_size + s_.data_length);
    }

    void send_batch(std::size_t n) {
        std::size_t done = 0;
        while (done < n) {
            const int r = sendmmsg(fd_, msgs_.data() + done, static_cast<unsigned>(n - done), 0);
            if (r < 0) {
                if (errno == EINTR) continue;
                ++errors_;  // e.g. ECONNREFUSED from an earlier ICMP: skip one datagram
                ++done;
                continue;
            }
            done += static_cast<std::size_t>(r);
            sent_ += static_cast<std::uint64_t>(r);
        }
    }

    const Settings& s_;
    int fd_;
    std::vector<Exchange> state_;
    std::vector<std::vector<unsigned char>> slots_;
    std::vector<iovec> iov_;
    std::vector<mmsghdr> msgs_;
    std::uint64_t sent_ = 0;
    std::uint64_t errors_ = 0;
};

/// Sends the schedule's datagrams, each batch slot's due ones at once; returns the seconds taken.
double run(const Settings& s, Generator& generator) {
    const std::int64_t start = bench::mono_ns();
    std::uint64_t scheduled = 0;
    for (std::int64_t batch = 1; scheduled < s.total; ++batch) {
        // Datagrams due by the end of this batch slot, from the absolute schedule.
        const auto due = std::min<std::uint64_t>(
            s.total, static_cast<std::uint64_t>(static_cast<double>(batch) *
                                                static_cast<double>(s.batch_ns) * s.rate / 1e9));
        generator.send_range(scheduled, due, std::nullopt);
        scheduled = due;
        const std::int64_t deadline = start + batch * s.batch_ns;
        if (bench::mono_ns() < deadline) bench::sleep_until_mono(deadline);
    }
    return static_cast<double>(bench::mono_ns() - start) / 1e9;
}

}  // namespace

int main(int argc, char** argv) {
    const Settings s = read_settings(argc, argv);
    const int fd = connect_socket(s);
    Generator generator(s, fd);
    const double elapsed = run(s, generator);
    const std::uint64_t final_sent =
        s.final_value ? generator.send_final(s.total, *s.final_value) : 0;
    std::printf(
        "{\"sent\":%llu,\"final\":%llu,\"errors\":%llu,\"elapsed_s\":%.4f,\"rate\":%.1f,"
        "\"length\":%zu,\"changes\":%zu}\n",
        static_cast<unsigned long long>(generator.sent()),
        static_cast<unsigned long long>(final_sent),
        static_cast<unsigned long long>(generator.errors()), elapsed,
        static_cast<double>(generator.sent()) / elapsed, s.data_length, s.changes);
    close(fd);
    return 0;
}
