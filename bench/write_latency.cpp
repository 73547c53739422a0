// write_latency: how long an MQTT write takes to reach the wire (issue #6). Publishes writes to
// a produced exchange's tag `/set` topic at --rate writes/s (QoS 1, not retained, each a new
// dint value) and listens on the exchange's UDP destination, decoding the produced datagrams
// (32-byte header, then data; docs/protocol.md §2) for the tag at data byte --offset. The
// latency of a write = kernel receive time (SO_TIMESTAMPNS, CLOCK_REALTIME) of the first
// datagram of --exchange-id whose value is the written one or a later one (writes are applied
// in order, so a later value proves the earlier write was applied too) - CLOCK_REALTIME just
// before mosquitto_publish. Same clock, same process. Also counts the `{"ok":true}` results on
// `{set topic}/result`, and, as the same-run baseline, subscribes to the `/set` topic itself:
// publish -> delivery back to this client is the broker hop every write pays before the
// gateway sees it.
//
// Prints one JSON line: writes, seen (writes found on the wire), results, p50/p99/max/mean ms,
// and hop_p50_ms/hop_p99_ms.

#include <mosquitto.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "mosquitto_session.hpp"

namespace {

struct State {
    std::string topic;
    std::string result_topic;
    std::int32_t first_value = 0;
    std::vector<std::atomic<std::int64_t>>* published_at = nullptr;
    std::mutex mutex;
    std::vector<std::int64_t> hop_ns;  ///< guarded by mutex
    std::string ready_file;
    std::atomic<int> subscribed{0};
    std::atomic<std::uint64_t> results_ok{0};
};

void on_connect(mosquitto* mosq, void* user, int rc) {
    auto& s = *static_cast<State*>(user);
    if (rc != 0) {
        std::fprintf(stderr, "write_latency: connect refused (%d)\n", rc);
        return;
    }
    mosquitto_subscribe(mosq, nullptr, s.result_topic.c_str(), 1);
    mosquitto_subscribe(mosq, nullptr, s.topic.c_str(), 1);
}

void on_subscribe(mosquitto*, void* user, int, int, const int*) {
    ++static_cast<State*>(user)->subscribed;
}

void on_message(mosquitto*, void* user, const mosquitto_message* msg) {
    auto& s = *static_cast<State*>(user);
    const auto* payload = static_cast<const char*>(msg->payload);
    if (s.topic == msg->topic) {
        const std::int64_t now = bench::wall_ns();
        const std::string text(payload, static_cast<std::size_t>(msg->payloadlen));
        const long long index = std::strtoll(text.c_str(), nullptr, 10) - s.first_value;
        if (index < 0 || index >= static_cast<long long>(s.published_at->size())) return;
        const auto sent = (*s.published_at)[static_cast<std::size_t>(index)].load();
        std::lock_guard lock(s.mutex);
        if (sent != 0) s.hop_ns.push_back(now - sent);
        return;
    }
    if (msg->payloadlen >= 10 && std::memcmp(payload, "{\"ok\":true", 10) == 0) ++s.results_ok;
}

std::int64_t timespec_ns(const timespec& ts) {
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
}

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(argc, argv,
                             {"host", "port", "udp-port", "topic", "exchange-id", "offset", "rate",
                              "count", "first-value", "ready-file", "id", "settle-ms"});
    State s;
    const std::string topic = opt.str("topic", "");
    if (topic.empty()) bench::Options::fail("--topic is required");
    s.topic = topic;
    s.result_topic = topic + "/result";
    const auto exchange_id = static_cast<std::uint32_t>(opt.num("exchange-id", 1));
    const auto offset = static_cast<std::size_t>(opt.num("offset", 8));
    const double rate = opt.num("rate", 50);
    const auto count = static_cast<std::size_t>(opt.num("count", 500));
    const auto first_value = static_cast<std::int32_t>(opt.num("first-value", 1000000));
    std::vector<std::atomic<std::int64_t>> published_at(count);  ///< CLOCK_REALTIME ns by index
    s.first_value = first_value;
    s.published_at = &published_at;
    const auto settle_ns = static_cast<std::int64_t>(opt.num("settle-ms", 1000) * 1e6);

    // The exchange's destination: bound before the first write, so no datagram is missed.
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
    const int rcvbuf = 8 << 20;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(opt.num("udp-port", 18246)));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        bench::Options::fail("cannot bind the UDP port");
    }

    // Like the broker (set_tcp_nodelay) and the gateway: without it Nagle and delayed ACKs add
    // up to 40 ms to each write, which would measure the bench's client, not the gateway.
    mosquitto* mosq = bench::start_mosquitto(opt, "bench-writer", &s,
                                             {on_connect, on_subscribe, on_message}, true);
    for (const auto deadline = bench::mono_ns() + 5'000'000'000; s.subscribed < 2;) {
        if (bench::mono_ns() > deadline) bench::Options::fail("no subscription acknowledged");
        usleep(1000);
    }
    bench::touch(opt.str("ready-file", ""));

    std::vector<std::int64_t> latency_ns;
    std::size_t published = 0;
    std::size_t seen = 0;  ///< writes [0, seen) were found on the wire
    const auto interval_ns = static_cast<std::int64_t>(1e9 / rate);
    const std::int64_t start = bench::mono_ns();
    std::int64_t end = 0;
    char payload[32];
    unsigned char buffer[2048];
    alignas(cmsghdr) char control[256];
    for (;;) {
        const std::int64_t now = bench::mono_ns();
        if (published < count &&
            now >= start + static_cast<std::int64_t>(published) * interval_ns) {
            const auto value = first_value + static_cast<std::int32_t>(published);
            const int n = std::snprintf(payload, sizeof payload, "%d", value);
            published_at[published].store(bench::wall_ns());
            mosquitto_publish(mosq, nullptr, topic.c_str(), n, payload, 1, false);
            if (++published == count) end = now + settle_ns;
            continue;
        }
        if (end != 0 && (now >= end || (seen == count && s.results_ok >= count))) break;
        const std::int64_t next_write =
            published < count ? start + static_cast<std::int64_t>(published) * interval_ns : end;
        pollfd p{fd, POLLIN, 0};
        const int timeout_ms =
            static_cast<int>(std::max<std::int64_t>(0, next_write - now) / 1000000);
        if (poll(&p, 1, timeout_ms) <= 0) continue;
        iovec iov{buffer, sizeof buffer};
        msghdr hdr{};
        hdr.msg_iov = &iov;
        hdr.msg_iovlen = 1;
        hdr.msg_control = control;
        hdr.msg_controllen = sizeof control;
        const auto size = recvmsg(fd, &hdr, MSG_DONTWAIT);
        if (size < static_cast<ssize_t>(32 + offset + 4)) continue;
        std::int64_t received = bench::wall_ns();
        for (cmsghdr* c = CMSG_FIRSTHDR(&hdr); c != nullptr; c = CMSG_NXTHDR(&hdr, c)) {
            if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
                timespec ts{};
                std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
                received = timespec_ns(ts);
            }
        }
        std::uint32_t id = 0;  // docs/protocol.md §2: exchange id, u32 little-endian at byte 8
        for (int i = 3; i >= 0; --i) id = id << 8 | buffer[8 + i];
        if (id != exchange_id) continue;
        std::uint32_t raw = 0;  // the dint at data byte `offset`, little-endian
        for (int i = 3; i >= 0; --i)
            raw = raw << 8 | buffer[32 + offset + static_cast<std::size_t>(i)];
        const auto value = static_cast<std::int32_t>(raw);
        // Every write up to this value was applied before this datagram was produced.
        while (seen < published && first_value + static_cast<std::int32_t>(seen) <= value) {
            latency_ns.push_back(received - published_at[seen].load());
            ++seen;
        }
    }
    mosquitto_disconnect(mosq);
    mosquitto_loop_stop(mosq, true);
    close(fd);

    double mean = 0;
    for (const auto l : latency_ns) mean += static_cast<double>(l);
    if (!latency_ns.empty()) mean /= static_cast<double>(latency_ns.size());
    const double p50 = static_cast<double>(bench::percentile(latency_ns, 0.50)) / 1e6;
    const double p99 = static_cast<double>(bench::percentile(latency_ns, 0.99)) / 1e6;
    const double max = latency_ns.empty() ? 0 : static_cast<double>(latency_ns.back()) / 1e6;
    std::lock_guard lock(s.mutex);
    const double hop_p50 = static_cast<double>(bench::percentile(s.hop_ns, 0.50)) / 1e6;
    const double hop_p99 = static_cast<double>(bench::percentile(s.hop_ns, 0.99)) / 1e6;
    std::printf(
        "{\"writes\":%zu,\"seen\":%zu,\"results_ok\":%llu,\"p50_ms\":%.3f,\"p99_ms\":%.3f,"
        "\"max_ms\":%.3f,\"mean_ms\":%.3f,\"hops\":%zu,\"hop_p50_ms\":%.3f,"
        "\"hop_p99_ms\":%.3f}\n",
        published, seen, static_cast<unsigned long long>(s.results_ok.load()), p50, p99, max,
        mean / 1e6, s.hop_ns.size(), hop_p50, hop_p99);
    mosquitto_lib_cleanup();
    return 0;
}
