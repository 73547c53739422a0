// udp_sink: the bare UDP ceiling: a recvmmsg receiver doing nothing but counting, with the same
// receive buffer request as the gateway (8 MiB, capped by net.core.rmem_max).
//
// Count mode (default): stops after --idle-ms without a datagram (once one arrived) or after
// --max-s; prints received, first_to_last_s, rate.
//
// Period mode (--period-ms P): keeps the kernel receive time (SO_TIMESTAMPNS) of every datagram
// by exchange id (bytes 8..11), skips the first --skip-ms, and prints per-exchange period
// statistics: mean period, mean error (%) overall and worst exchange, p99 and max jitter
// (|interval - P|) over all intervals.

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "bench_common.hpp"

namespace {

constexpr std::size_t batch = 64;
constexpr std::size_t slot_size = 2048;
constexpr std::size_t control_size = CMSG_SPACE(sizeof(timespec));

struct Settings {
    bool periods = false;  ///< period mode
    double period_ns = 0;
    std::int64_t idle_ns = 0;
    std::int64_t max_ns = 0;
    std::int64_t duration_ns = 0;
    std::int64_t skip_ns = 0;
    std::string bind;
    std::uint16_t port = 0;
    std::string ready_file;
};

Settings read_settings(int argc, char** argv) {
    const bench::Options opt(
        argc, argv,
        {"bind", "port", "idle-ms", "max-s", "period-ms", "skip-ms", "duration", "ready-file"});
    Settings s;
    s.periods = opt.has("period-ms");
    s.period_ns = opt.num("period-ms", 10) * 1e6;
    s.idle_ns = static_cast<std::int64_t>(opt.num("idle-ms", 1000) * 1e6);
    s.max_ns = static_cast<std::int64_t>(opt.num("max-s", 60) * 1e9);
    s.duration_ns = static_cast<std::int64_t>(opt.num("duration", 0) * 1e9);
    s.skip_ns = static_cast<std::int64_t>(opt.num("skip-ms", 500) * 1e6);
    s.bind = opt.str("bind", "127.0.0.1");
    s.port = static_cast<std::uint16_t>(opt.num("port", 18246));
    s.ready_file = opt.str("ready-file", "");
    return s;
}

int bind_socket(const Settings& s) {
    const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
    const int rcvbuf = 8 * 1024 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    if (s.periods) setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(s.port);
    inet_pton(AF_INET, s.bind.c_str(), &addr.sin_addr);
    if (::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        bench::Options::fail(std::string("bind: ") + std::strerror(errno));
    }
    return fd;
}

/// Receives in batches of up to `batch` datagrams and counts them; in period mode, keeps the
/// arrival time of each by exchange id.
class Sink {
public:
    Sink(const Settings& s, int fd)
        : s_(s),
          fd_(fd),
          storage_(batch * slot_size),
          control_(batch * control_size),
          iov_(batch),
          msgs_(batch) {}

    /// Receives until idle, the duration or the maximum time is over.
    void run() {
        const std::int64_t start = bench::mono_ns();
        pollfd pfd{fd_, POLLIN, 0};
        for (;;) {
            const std::int64_t now = bench::mono_ns();
            if (now - start > s_.max_ns) break;
            if (s_.duration_ns > 0 && now - start > s_.duration_ns) break;
            if (s_.duration_ns == 0 && received_ > 0 && now - last_ > s_.idle_ns) break;
            if (poll(&pfd, 1, 50) <= 0) continue;
            while (receive_batch()) {
            }
        }
    }

    void print_count() const {
        const double span = static_cast<double>(last_ - first_) / 1e9;
        std::printf("{\"received\":%llu,\"first_to_last_s\":%.4f,\"rate\":%.1f}\n",
                    static_cast<unsigned long long>(received_), span,
                    span > 0 ? static_cast<double>(received_) / span : 0.0);
    }

    void print_periods();

private:
    /// One recvmmsg; false when nothing was waiting.
    bool receive_batch() {
        for (std::size_t i = 0; i < batch; ++i) {
            iov_[i] = {storage_.data() + i * slot_size, slot_size};
            msgs_[i] = {};
            msgs_[i].msg_hdr.msg_iov = &iov_[i];
            msgs_[i].msg_hdr.msg_iovlen = 1;
            if (s_.periods) {
                msgs_[i].msg_hdr.msg_control = control_.data() + i * control_size;
                msgs_[i].msg_hdr.msg_controllen = control_size;
            }
        }
        const int n = recvmmsg(fd_, msgs_.data(), batch, MSG_DONTWAIT, nullptr);
        if (n <= 0) return false;
        last_ = bench::mono_ns();
        if (received_ == 0) first_ = last_;
        received_ += static_cast<std::uint64_t>(n);
        if (s_.periods) record_arrivals(static_cast<std::size_t>(n));
        return true;
    }

    void record_arrivals(std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) {
            if (msgs_[i].msg_len < 32) continue;
            const std::int64_t t = bench::kernel_receive_ns(msgs_[i].msg_hdr, bench::wall_ns());
            if (first_wall_ == 0) first_wall_ = t;
            if (t - first_wall_ < s_.skip_ns) continue;
            std::uint32_t exchange = 0;
            std::memcpy(&exchange, static_cast<unsigned char*>(iov_[i].iov_base) + 8, 4);
            arrivals_[exchange].push_back(t);
        }
    }

    const Settings& s_;
    int fd_;
    std::vector<unsigned char> storage_;
    std::vector<unsigned char> control_;
    std::vector<iovec> iov_;
    std::vector<mmsghdr> msgs_;
    std::int64_t first_ = 0;
    std::int64_t last_ = 0;
    std::int64_t first_wall_ = 0;
    std::uint64_t received_ = 0;
    /// Arrival times (realtime ns, kernel stamp) by exchange id: period mode only.
    std::unordered_map<std::uint32_t, std::vector<std::int64_t>> arrivals_;
};

void Sink::print_periods() {
    const double period_ns = s_.period_ns;
    std::vector<double> jitter;
    double sum_intervals = 0;
    std::uint64_t intervals = 0;
    double worst_error = 0;
    for (auto& [exchange, times] : arrivals_) {
        if (times.size() < 2) continue;
        std::sort(times.begin(), times.end());
        for (std::size_t i = 1; i < times.size(); ++i) {
            jitter.push_back(std::fabs(static_cast<double>(times[i] - times[i - 1]) - period_ns));
        }
        const double mean = static_cast<double>(times.back() - times.front()) /
                            static_cast<double>(times.size() - 1);
        worst_error = std::max(worst_error, std::fabs(mean - period_ns) / period_ns * 100);
        sum_intervals += static_cast<double>(times.back() - times.front());
        intervals += times.size() - 1;
    }
    const double mean_period = intervals > 0 ? sum_intervals / static_cast<double>(intervals) : 0;
    const double p99 = bench::percentile(jitter, 0.99);
    const double max = jitter.empty() ? 0 : jitter.back();
    std::printf(
        "{\"received\":%llu,\"exchanges\":%zu,\"intervals\":%llu,\"mean_period_ms\":%.6f,"
        "\"mean_error_pct\":%.5f,\"worst_exchange_error_pct\":%.5f,\"p50_jitter_us\":%.1f,"
        "\"p99_jitter_us\":%.1f,\"max_jitter_us\":%.1f}\n",
        static_cast<unsigned long long>(received_), arrivals_.size(),
        static_cast<unsigned long long>(intervals), mean_period / 1e6,
        std::fabs(mean_period - period_ns) / period_ns * 100, worst_error,
        bench::percentile(jitter, 0.5) / 1e3, p99 / 1e3, max / 1e3);
}

}  // namespace

int main(int argc, char** argv) {
    const Settings s = read_settings(argc, argv);
    const int fd = bind_socket(s);
    Sink sink(s, fd);
    bench::touch(s.ready_file);
    sink.run();
    if (s.periods) {
        sink.print_periods();
    } else {
        sink.print_count();
    }
    return 0;
}
