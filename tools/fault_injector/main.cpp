// eip2mqtt-fault-injector: a UDP proxy that loses, delays, duplicates, reorders, truncates and
// corrupts EIP datagrams on their way to a consumer, with a seeded RNG so that a run can be
// repeated. The decisions are made by FaultModel (fault_model.hpp); this file only moves bytes.

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <queue>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/wire/header.hpp"
#include "tools/fault_injector/fault_model.hpp"

namespace {

using eip2mqtt::fault_injector::Emission;
using eip2mqtt::fault_injector::FaultConfig;
using eip2mqtt::fault_injector::FaultModel;
using Clock = std::chrono::steady_clock;

constexpr const char* usage =
    R"(usage: eip2mqtt-fault-injector --listen [HOST:]PORT --to HOST:PORT [options]

Forwards UDP datagrams from --listen to --to, injecting faults with a seeded RNG
(same seed + same input = same decisions). Probabilities P are 0..1, per datagram.

  --listen [HOST:]PORT   where to receive (default host 0.0.0.0; port 0 picks one)
  --to HOST:PORT         where to forward (e.g. the gateway, 127.0.0.1:18246)
  --seed N               RNG seed (default 1)
  --loss P               lose the datagram
  --loss-burst N         each loss drops N datagrams in a row (default 1)
  --delay MS             delay every datagram by MS
  --jitter P:MS          delay the datagram by MS more, with probability P
  --duplicate P          send the datagram twice
  --reorder P            hold the datagram and send it after the next one
  --truncate P[:LEN]     cut it to LEN bytes (random length when LEN is absent or too large)
  --corrupt-byte P[:OFF] XOR the byte at OFF with a random non-zero value (random OFF if absent)
  --corrupt-bit P[:OFF]  flip bit OFF (byte * 8 + bit; random if absent)
  --corrupt-field P:NAME set a header field to another value; NAME is one of type, version,
                         rid, producer, exchange, time, status, signature, reserved
  --count N              stop after N datagrams received
  --duration S           stop after S seconds
  --report-json FILE     also write the report as JSON
Stops on --count, --duration, SIGINT or SIGTERM; delayed datagrams still due are then sent,
and the report (datagrams in/out, per fault: probability and affected count) is printed.
)";

volatile sig_atomic_t stop_requested = 0;

void on_signal(int) { stop_requested = 1; }

struct Options {
    std::string listen_host = "0.0.0.0";
    std::uint16_t listen_port = eip2mqtt::core::wire::default_port;
    std::string to_host;
    std::uint16_t to_port = 0;
    std::optional<std::uint64_t> count;
    std::optional<double> duration_s;
    std::string report_json;
    FaultConfig faults;
};

[[noreturn]] void die(const std::string& message, int code = 1) {
    std::fprintf(stderr, "eip2mqtt-fault-injector: %s\n", message.c_str());
    std::exit(code);
}

bool parse_port(std::string_view text, std::uint16_t& port) {
    if (text.empty() || text.size() > 5) return false;
    unsigned long v = 0;
    for (const char c : text) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + static_cast<unsigned long>(c - '0');
    }
    if (v > 65535) return false;
    port = static_cast<std::uint16_t>(v);
    return true;
}

bool parse_host_port(std::string_view text, std::string& host, std::uint16_t& port,
                     bool host_optional) {
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos) {
        return host_optional && parse_port(text, port);
    }
    host = std::string(text.substr(0, colon));
    return !host.empty() && parse_port(text.substr(colon + 1), port);
}

Options parse_args(int argc, char** argv) {
    Options options;
    bool have_to = false;
    for (int i = 1; i < argc; ++i) {
        std::string_view arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::fputs(usage, stdout);
            std::exit(0);
        }
        if (arg.substr(0, 2) != "--") die("unexpected argument '" + std::string(arg) + "'", 2);
        arg.remove_prefix(2);
        std::string_view value;
        if (const auto eq = arg.find('='); eq != std::string_view::npos) {
            value = arg.substr(eq + 1);
            arg = arg.substr(0, eq);
        } else {
            if (i + 1 >= argc) die("--" + std::string(arg) + " needs a value", 2);
            value = argv[++i];
        }
        if (arg == "listen") {
            if (!parse_host_port(value, options.listen_host, options.listen_port, true)) {
                die("--listen: expected [HOST:]PORT, got '" + std::string(value) + "'", 2);
            }
        } else if (arg == "to") {
            if (!parse_host_port(value, options.to_host, options.to_port, false)) {
                die("--to: expected HOST:PORT, got '" + std::string(value) + "'", 2);
            }
            have_to = true;
        } else if (arg == "count") {
            char* end = nullptr;
            const std::string text(value);
            const auto n = std::strtoull(text.c_str(), &end, 10);
            if (text.empty() || *end != '\0') die("--count: expected a number", 2);
            options.count = n;
        } else if (arg == "duration") {
            char* end = nullptr;
            const std::string text(value);
            const double s = std::strtod(text.c_str(), &end);
            if (text.empty() || *end != '\0' || !(s >= 0)) die("--duration: expected seconds", 2);
            options.duration_s = s;
        } else if (arg == "report-json") {
            options.report_json = std::string(value);
        } else if (const auto applied = apply_option(options.faults, arg, value); !applied) {
            die(applied.error(), 2);
        }
    }
    if (!have_to) die("--to HOST:PORT is required (see --help)", 2);
    return options;
}

sockaddr_in resolve(const std::string& host, std::uint16_t port) {
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_DGRAM;
    addrinfo* result = nullptr;
    if (const int rc = ::getaddrinfo(host.c_str(), nullptr, &hints, &result); rc != 0) {
        die("cannot resolve '" + host + "': " + ::gai_strerror(rc));
    }
    sockaddr_in address{};
    std::memcpy(&address, result->ai_addr, sizeof address);
    ::freeaddrinfo(result);
    address.sin_port = htons(port);
    return address;
}

std::string to_string(const sockaddr_in& address) {
    char text[INET_ADDRSTRLEN] = {};
    ::inet_ntop(AF_INET, &address.sin_addr, text, sizeof text);
    return std::string(text) + ":" + std::to_string(ntohs(address.sin_port));
}

int open_socket(const sockaddr_in* bind_to) {
    const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0) die(std::string("socket: ") + std::strerror(errno));
    // Bursts from a test or a simulator must not be lost before the injector decides anything:
    // ask for a large buffer (the kernel caps it at net.core.rmem_max).
    const int buffer = 8 * 1024 * 1024;
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof buffer);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &buffer, sizeof buffer);
    if (bind_to != nullptr) {
        const int one = 1;
        ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        if (::bind(fd, reinterpret_cast<const sockaddr*>(bind_to), sizeof *bind_to) != 0) {
            die("cannot bind " + to_string(*bind_to) + ": " + std::strerror(errno));
        }
    }
    return fd;
}

struct Pending {
    Clock::time_point due;
    std::uint64_t sequence;  ///< keeps emissions due at the same time in decision order
    std::vector<std::byte> bytes;

    bool operator>(const Pending& other) const {
        return due != other.due ? due > other.due : sequence > other.sequence;
    }
};

class Proxy {
public:
    Proxy(const Options& options) : options_(options), model_(options.faults) {
        const sockaddr_in listen_address = resolve(options.listen_host, options.listen_port);
        to_ = resolve(options.to_host, options.to_port);
        in_fd_ = open_socket(&listen_address);
        out_fd_ = open_socket(nullptr);
        sockaddr_in bound{};
        socklen_t length = sizeof bound;
        ::getsockname(in_fd_, reinterpret_cast<sockaddr*>(&bound), &length);
        std::printf("listening on %s, forwarding to %s, seed %llu\n", to_string(bound).c_str(),
                    to_string(to_).c_str(), static_cast<unsigned long long>(options.faults.seed));
        std::fflush(stdout);
    }

    ~Proxy() {
        ::close(in_fd_);
        ::close(out_fd_);
    }

    void run(const sigset_t& unblocked) {
        started_ = Clock::now();
        const std::optional<Clock::time_point> end =
            options_.duration_s
                ? std::optional(started_ + std::chrono::duration_cast<Clock::duration>(
                                               std::chrono::duration<double>(*options_.duration_s)))
                : std::nullopt;
        bool receiving = true;
        while (true) {
            const auto now = Clock::now();
            if (stop_requested) {
                // Stop at once: whatever is still due goes out now.
                schedule(model_.flush(), now);
                send_due(Clock::time_point::max());
                break;
            }
            if (receiving && (done_counting() || (end && now >= *end))) {
                receiving = false;
                schedule(model_.flush(), now);
            }
            send_due(now);
            if (!receiving && pending_.empty()) break;

            std::optional<Clock::time_point> wake;
            if (!pending_.empty()) wake = pending_.top().due;
            if (receiving && end && (!wake || *end < *wake)) wake = end;
            timespec timeout{};
            timespec* timeout_ptr = nullptr;
            if (wake) {
                const auto wait = std::max(Clock::duration::zero(), *wake - now);
                const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(wait).count();
                timeout.tv_sec = static_cast<time_t>(ns / 1000000000);
                timeout.tv_nsec = static_cast<long>(ns % 1000000000);
                timeout_ptr = &timeout;
            }
            pollfd fd{in_fd_, static_cast<short>(receiving ? POLLIN : 0), 0};
            // Signals are blocked except inside ppoll, so a SIGTERM cannot slip in between the
            // check of stop_requested above and the wait.
            const int ready = ::ppoll(&fd, 1, timeout_ptr, &unblocked);
            if (ready < 0 && errno != EINTR) die(std::string("poll: ") + std::strerror(errno));
            if (ready > 0 && (fd.revents & POLLIN) != 0) receive();
        }
    }

    void report() const {
        const double seconds = std::chrono::duration<double>(Clock::now() - started_).count();
        std::fputs(format_report(model_, seconds).c_str(), stdout);
        if (send_errors_ > 0) {
            std::printf("send errors: %llu\n", static_cast<unsigned long long>(send_errors_));
        }
        std::fflush(stdout);
        if (!options_.report_json.empty()) {
            std::ofstream file(options_.report_json);
            file << format_report_json(model_, seconds);
            if (!file) die("cannot write " + options_.report_json);
        }
    }

private:
    bool done_counting() const { return options_.count && model_.counters().in >= *options_.count; }

    void receive() {
        std::vector<std::byte> buffer(65536);
        // A bounded batch per wake-up, so that due emissions are not starved by a flood.
        for (int i = 0; i < 256 && !done_counting(); ++i) {
            const ssize_t n = ::recv(in_fd_, buffer.data(), buffer.size(), 0);
            if (n < 0) {
                if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return;
                die(std::string("recv: ") + std::strerror(errno));
            }
            const auto now = Clock::now();
            schedule(model_.on_datagram({buffer.begin(), buffer.begin() + n}), now);
            send_due(now);
        }
    }

    void schedule(std::vector<Emission> emissions, Clock::time_point now) {
        for (auto& e : emissions)
            pending_.push({now + e.delay, next_sequence_++, std::move(e.bytes)});
    }

    void send_due(Clock::time_point now) {
        while (!pending_.empty() && pending_.top().due <= now) {
            const auto& p = pending_.top();
            if (::sendto(out_fd_, p.bytes.data(), p.bytes.size(), 0,
                         reinterpret_cast<const sockaddr*>(&to_), sizeof to_) < 0) {
                ++send_errors_;
            }
            pending_.pop();
        }
    }

    const Options& options_;
    FaultModel model_;
    sockaddr_in to_{};
    int in_fd_ = -1;
    int out_fd_ = -1;
    Clock::time_point started_;
    std::priority_queue<Pending, std::vector<Pending>, std::greater<>> pending_;
    std::uint64_t next_sequence_ = 0;
    std::uint64_t send_errors_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    const Options options = parse_args(argc, argv);

    // Signals set a flag; the loop acts on it.
    struct sigaction action {};
    action.sa_handler = on_signal;
    ::sigemptyset(&action.sa_mask);
    ::sigaction(SIGINT, &action, nullptr);
    ::sigaction(SIGTERM, &action, nullptr);
    sigset_t blocked;
    sigset_t unblocked;
    ::sigemptyset(&blocked);
    ::sigaddset(&blocked, SIGINT);
    ::sigaddset(&blocked, SIGTERM);
    ::sigprocmask(SIG_BLOCK, &blocked, &unblocked);
    ::sigdelset(&unblocked, SIGINT);
    ::sigdelset(&unblocked, SIGTERM);

    Proxy proxy(options);
    proxy.run(unblocked);
    proxy.report();
    return 0;
}
