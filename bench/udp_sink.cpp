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
#include <unordered_map>
#include <vector>

#include "bench_common.hpp"

namespace {

constexpr std::size_t batch = 64;
constexpr std::size_t slot_size = 2048;
constexpr std::size_t control_size = CMSG_SPACE(sizeof(timespec));

}  // namespace

int main(int argc, char** argv) {
    const bench::Options opt(
        argc, argv,
        {"bind", "port", "idle-ms", "max-s", "period-ms", "skip-ms", "duration", "ready-file"});
    const bool periods = opt.has("period-ms");
    const double period_ns = opt.num("period-ms", 10) * 1e6;
    const auto idle_ns = static_cast<std::int64_t>(opt.num("idle-ms", 1000) * 1e6);
    const auto max_ns = static_cast<std::int64_t>(opt.num("max-s", 60) * 1e9);
    const auto duration_ns = static_cast<std::int64_t>(opt.num("duration", 0) * 1e9);
    const auto skip_ns = static_cast<std::int64_t>(opt.num("skip-ms", 500) * 1e6);

    const int fd = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK, 0);
    const int rcvbuf = 8 * 1024 * 1024;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &rcvbuf, sizeof rcvbuf);
    const int on = 1;
    setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    if (periods) setsockopt(fd, SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<std::uint16_t>(opt.num("port", 18246)));
    inet_pton(AF_INET, opt.str("bind", "127.0.0.1").c_str(), &addr.sin_addr);
    if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        bench::Options::fail(std::string("bind: ") + std::strerror(errno));
    }

    std::vector<unsigned char> storage(batch * slot_size);
    std::vector<unsigned char> control(batch * control_size);
    std::vector<iovec> iov(batch);
    std::vector<mmsghdr> msgs(batch);
    // Arrival times (realtime ns, kernel stamp) by exchange id: period mode only.
    std::unordered_map<std::uint32_t, std::vector<std::int64_t>> arrivals;

    bench::touch(opt.str("ready-file", ""));
    const std::int64_t start = bench::mono_ns();
    std::int64_t first = 0;
    std::int64_t last = 0;
    std::int64_t first_wall = 0;
    std::uint64_t received = 0;
    pollfd pfd{fd, POLLIN, 0};
    for (;;) {
        const std::int64_t now = bench::mono_ns();
        if (now - start > max_ns) break;
        if (duration_ns > 0 && now - start > duration_ns) break;
        if (duration_ns == 0 && received > 0 && now - last > idle_ns) break;
        if (poll(&pfd, 1, 50) <= 0) continue;
        for (;;) {
            for (std::size_t i = 0; i < batch; ++i) {
                iov[i] = {storage.data() + i * slot_size, slot_size};
                msgs[i] = {};
                msgs[i].msg_hdr.msg_iov = &iov[i];
                msgs[i].msg_hdr.msg_iovlen = 1;
                if (periods) {
                    msgs[i].msg_hdr.msg_control = control.data() + i * control_size;
                    msgs[i].msg_hdr.msg_controllen = control_size;
                }
            }
            const int n = recvmmsg(fd, msgs.data(), batch, MSG_DONTWAIT, nullptr);
            if (n <= 0) break;
            last = bench::mono_ns();
            if (received == 0) first = last;
            received += static_cast<std::uint64_t>(n);
            if (!periods) continue;
            for (int i = 0; i < n; ++i) {
                const auto& hdr = msgs[static_cast<std::size_t>(i)].msg_hdr;
                if (msgs[static_cast<std::size_t>(i)].msg_len < 32) continue;
                std::int64_t t = bench::wall_ns();
                for (cmsghdr* c = CMSG_FIRSTHDR(&hdr); c != nullptr;
                     c = CMSG_NXTHDR(const_cast<msghdr*>(&hdr), c)) {
                    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
                        timespec ts{};
                        std::memcpy(&ts, CMSG_DATA(c), sizeof ts);
                        t = static_cast<std::int64_t>(ts.tv_sec) * 1000000000 + ts.tv_nsec;
                    }
                }
                if (first_wall == 0) first_wall = t;
                if (t - first_wall < skip_ns) continue;
                std::uint32_t exchange = 0;
                std::memcpy(
                    &exchange,
                    static_cast<unsigned char*>(iov[static_cast<std::size_t>(i)].iov_base) + 8, 4);
                arrivals[exchange].push_back(t);
            }
        }
    }
    const double span = static_cast<double>(last - first) / 1e9;
    if (!periods) {
        std::printf("{\"received\":%llu,\"first_to_last_s\":%.4f,\"rate\":%.1f}\n",
                    static_cast<unsigned long long>(received), span,
                    span > 0 ? static_cast<double>(received) / span : 0.0);
        return 0;
    }
    std::vector<double> jitter;
    double sum_intervals = 0;
    std::uint64_t intervals = 0;
    double worst_error = 0;
    for (auto& [exchange, times] : arrivals) {
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
        static_cast<unsigned long long>(received), arrivals.size(),
        static_cast<unsigned long long>(intervals), mean_period / 1e6,
        std::fabs(mean_period - period_ns) / period_ns * 100, worst_error,
        bench::percentile(jitter, 0.5) / 1e3, p99 / 1e3, max / 1e3);
    return 0;
}
