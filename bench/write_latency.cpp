// write_latency: how long an MQTT write takes to reach the wire. Publishes writes to
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

struct Settings {
    std::string topic;
    std::uint32_t exchange_id = 0;
    std::size_t offset = 0;  ///< of the written dint in the datagram's data
    double rate = 0;
    std::size_t count = 0;
    std::int32_t first_value = 0;
    std::int64_t settle_ns = 0;
    std::uint16_t udp_port = 0;
};

Settings read_settings(const bench::Options& opt) {
    Settings s;
    s.topic = opt.str("topic", "");
    if (s.topic.empty()) bench::Options::fail("--topic is required");
    s.exchange_id = static_cast<std::uint32_t>(opt.num("exchange-id", 1));
    s.offset = static_cast<std::size_t>(opt.num("offset", 8));
    s.rate = opt.num("rate", 50);
    s.count = static_cast<std::size_t>(opt.num("count", 500));
    s.first_value = static_cast<std::int32_t>(opt.num("first-value", 1000000));
    s.settle_ns = static_cast<std::int64_t>(opt.num("settle-ms", 1000) * 1e6);
    s.udp_port = static_cast<std::uint16_t>(opt.num("udp-port", 18246));
    return s;
}

/// The exchange's destination: bound before the first write, so no datagram is missed.
int bind_destination(std::uint16_t port) {
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
    const int rcvbuf = 8 << 20;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        bench::Options::fail("cannot bind the UDP port");
    }
    return fd;
}

/// Publishes the writes on schedule and finds them in the produced datagrams.
class Writer {
public:
    Writer(const Settings& s, State& state, mosquitto* mosq, int fd,
           std::vector<std::atomic<std::int64_t>>& published_at)
        : s_(s), state_(state), mosq_(mosq), fd_(fd), published_at_(published_at) {}

    /// Writes every value, then waits until each is seen (and answered) or the settling time
    /// after the last write is over.
    void run() {
        const auto interval_ns = static_cast<std::int64_t>(1e9 / s_.rate);
        const std::int64_t start = bench::mono_ns();
        std::int64_t end = 0;
        for (;;) {
            const std::int64_t now = bench::mono_ns();
            const std::int64_t next_write =
                start + static_cast<std::int64_t>(published_) * interval_ns;
            if (published_ < s_.count && now >= next_write) {
                publish_next();
                if (published_ == s_.count) end = now + s_.settle_ns;
                continue;
            }
            if (end != 0 && (now >= end || (seen_ == s_.count && state_.results_ok >= s_.count))) {
                break;
            }
            pollfd p{fd_, POLLIN, 0};
            const std::int64_t wake = published_ < s_.count ? next_write : end;
            const int timeout_ms =
                static_cast<int>(std::max<std::int64_t>(0, wake - now) / 1000000);
            if (poll(&p, 1, timeout_ms) > 0) receive();
        }
    }

    std::size_t published() const { return published_; }
    std::size_t seen() const { return seen_; }
    std::vector<std::int64_t>& latency_ns() { return latency_ns_; }

private:
    void publish_next() {
        char payload[32];
        const auto value = s_.first_value + static_cast<std::int32_t>(published_);
        const int n = std::snprintf(payload, sizeof payload, "%d", value);
        published_at_[published_].store(bench::wall_ns());
        mosquitto_publish(mosq_, nullptr, s_.topic.c_str(), n, payload, 1, false);
        ++published_;
    }

    /// One datagram: when it is the exchange's, the writes its value proves applied.
    void receive() {
        iovec iov{buffer_, sizeof buffer_};
        msghdr hdr{};
        hdr.msg_iov = &iov;
        hdr.msg_iovlen = 1;
        hdr.msg_control = control_;
        hdr.msg_controllen = sizeof control_;
        const auto size = recvmsg(fd_, &hdr, MSG_DONTWAIT);
        if (size < static_cast<ssize_t>(32 + s_.offset + 4)) return;
        const std::int64_t received = bench::kernel_receive_ns(hdr, bench::wall_ns());
        std::uint32_t id = 0;  // docs/protocol.md §2: exchange id, u32 little-endian at byte 8
        for (int i = 3; i >= 0; --i) id = id << 8 | buffer_[8 + i];
        if (id != s_.exchange_id) return;
        std::uint32_t raw = 0;  // the dint at data byte `offset`, little-endian
        for (int i = 3; i >= 0; --i) {
            raw = raw << 8 | buffer_[32 + s_.offset + static_cast<std::size_t>(i)];
        }
        const auto value = static_cast<std::int32_t>(raw);
        // Every write up to this value was applied before this datagram was produced.
        while (seen_ < published_ && s_.first_value + static_cast<std::int32_t>(seen_) <= value) {
            latency_ns_.push_back(received - published_at_[seen_].load());
            ++seen_;
        }
    }

    const Settings& s_;
    State& state_;
    mosquitto* mosq_;
    int fd_;
    std::vector<std::atomic<std::int64_t>>& published_at_;  ///< CLOCK_REALTIME ns by index
    std::vector<std::int64_t> latency_ns_;
    std::size_t published_ = 0;
    std::size_t seen_ = 0;  ///< writes [0, seen) were found on the wire
    unsigned char buffer_[2048];
    alignas(cmsghdr) char control_[256];
};

void print_report(Writer& writer, State& s) {
    auto& latency_ns = writer.latency_ns();
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
        writer.published(), writer.seen(), static_cast<unsigned long long>(s.results_ok.load()),
        p50, p99, max, mean / 1e6, s.hop_ns.size(), hop_p50, hop_p99);
}

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(argc, argv,
                             {"host", "port", "udp-port", "topic", "exchange-id", "offset", "rate",
                              "count", "first-value", "ready-file", "id", "settle-ms"});
    const Settings settings = read_settings(opt);
    std::vector<std::atomic<std::int64_t>> published_at(settings.count);
    State s;
    s.topic = settings.topic;
    s.result_topic = settings.topic + "/result";
    s.first_value = settings.first_value;
    s.published_at = &published_at;
    const int fd = bind_destination(settings.udp_port);

    // Like the broker (set_tcp_nodelay) and the gateway: without it Nagle and delayed ACKs add
    // up to 40 ms to each write, which would measure the bench's client, not the gateway.
    mosquitto* mosq = bench::start_mosquitto(opt, "bench-writer", &s,
                                             {on_connect, on_subscribe, on_message}, true);
    for (const auto deadline = bench::mono_ns() + 5'000'000'000; s.subscribed < 2;) {
        if (bench::mono_ns() > deadline) bench::Options::fail("no subscription acknowledged");
        usleep(1000);
    }
    bench::touch(opt.str("ready-file", ""));

    Writer writer(settings, s, mosq, fd, published_at);
    writer.run();
    mosquitto_disconnect(mosq);
    mosquitto_loop_stop(mosq, true);
    close(fd);
    print_report(writer, s);
    mosquitto_lib_cleanup();
    return 0;
}
