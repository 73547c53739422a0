#pragma once
/// What the tests of reloads with large files share: a produced exchange whose datagrams they
/// time, a plant of 100-tag consumed exchanges, recorders of produced datagrams, /healthz and
/// systemd notifications (each on a thread of its own, so that a stopped loop shows), and
/// ReloadLargeTest, which starts the gateway with them and reloads.

#include <signal.h>

#include <atomic>
#include <cstdio>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/notify_socket.hpp"

namespace eip2mqtt::test {

using namespace std::chrono_literals;
using ReloadClock = std::chrono::steady_clock;

/// The produced exchange whose datagrams the tests watch: every 20 ms to `port`.
inline std::string produced(std::uint16_t port) {
    return ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(port))
        .period_ms(20)
        .tag("VALUE", "0.0", "dint", "writable: true")
        .str();
}

/// A consumed exchange of 10.0.0.1 with one dint A, fed by the tests.
inline std::string kept() {
    return ExchangeYaml::consume("kept", "10.0.0.1", 1)
        .length(4)
        .period_ms(1000)
        .timeout_ms(0)
        .tag("A", "0.0", "dint")
        .str();
}

/// `exchanges` consumed exchanges of 100 dint tags each, written inline (as docs/configuration.md's
/// plant of 100,000 tags: 1,000 of them make 5.3 MB). With `unknown_key`, the last exchange
/// carries a key no exchange has, so the file is refused once it is read whole.
inline std::string plant(int exchanges, bool unknown_key = false) {
    std::string yaml;
    for (int e = 0; e < exchanges; ++e) {
        const auto name = "c" + std::to_string(e);
        yaml += "  - name: " + name + "\n    direction: consume\n    producer_id: 10.0.0.2\n" +
                "    exchange_id: " + std::to_string(e + 100) + "\n    topic: " + name +
                "\n    period_ms: 1000\n    timeout_ms: 0\n    tags:\n";
        for (int t = 0; t < 100; ++t) {
            yaml += "      - { name: T" + std::to_string(t) + ", address: \"" +
                    std::to_string(t * 4) + ".0\", type: dint }\n";
        }
    }
    if (unknown_key) yaml += "    colour: blue\n";
    return yaml;
}

/// Records the arrival of each datagram on a UDP socket, on a thread of its own.
class ArrivalRecorder {
public:
    ArrivalRecorder()
        : thread_([this] {
              while (!stop_) {
                  if (!socket_.receive(20ms)) continue;
                  std::lock_guard lock(mutex_);
                  arrivals_.push_back(ReloadClock::now());
              }
          }) {}
    ~ArrivalRecorder() {
        stop_ = true;
        thread_.join();
    }
    std::uint16_t port() const { return socket_.port(); }
    bool wait_first(std::chrono::milliseconds timeout) {
        const auto deadline = ReloadClock::now() + timeout;
        while (ReloadClock::now() < deadline) {
            if (std::lock_guard lock(mutex_); !arrivals_.empty()) return true;
            std::this_thread::sleep_for(10ms);
        }
        return false;
    }
    /// Arrivals strictly inside (from, to).
    std::vector<ReloadClock::time_point> between(ReloadClock::time_point from,
                                                 ReloadClock::time_point to) const {
        std::lock_guard lock(mutex_);
        std::vector<ReloadClock::time_point> out;
        for (const auto t : arrivals_) {
            if (t > from && t < to) out.push_back(t);
        }
        return out;
    }
    /// The longest time without an arrival within [from, to], its ends counting as arrivals.
    ReloadClock::duration longest_gap(ReloadClock::time_point from,
                                      ReloadClock::time_point to) const {
        auto last = from;
        ReloadClock::duration longest{};
        for (const auto t : between(from, to)) {
            longest = std::max(longest, t - last);
            last = t;
        }
        return std::max(longest, to - last);
    }

private:
    UdpClient socket_;
    mutable std::mutex mutex_;
    std::vector<ReloadClock::time_point> arrivals_;
    std::atomic<bool> stop_{false};
    std::thread thread_;  ///< last: starts once the rest is built
};

/// Polls /healthz every 100 ms on a thread of its own; keeps each answer that is not 200.
class HealthPoller {
public:
    explicit HealthPoller(std::uint16_t port)
        : thread_([this, port] {
              while (!stop_) {
                  const auto response = http_get(port, "/healthz");
                  {
                      std::lock_guard lock(mutex_);
                      ++polls_;
                      if (response.find(" 200 OK\r\n") == std::string::npos) {
                          failures_.push_back(response.empty() ? "(no answer)" : response);
                      }
                  }
                  std::this_thread::sleep_for(100ms);
              }
          }) {}
    ~HealthPoller() { stop(); }
    void stop() {
        stop_ = true;
        if (thread_.joinable()) thread_.join();
    }
    std::size_t polls() const {
        std::lock_guard lock(mutex_);
        return polls_;
    }
    std::vector<std::string> failures() const {
        std::lock_guard lock(mutex_);
        return failures_;
    }

private:
    mutable std::mutex mutex_;
    std::size_t polls_ = 0;
    std::vector<std::string> failures_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

/// Records, in order, what the gateway tells systemd, on a thread of its own.
class NotifyRecorder {
public:
    explicit NotifyRecorder(const std::string& path)
        : socket_(path), thread_([this] {
              while (!stop_) {
                  auto message = socket_.receive(50ms);
                  if (!message) continue;
                  std::lock_guard lock(mutex_);
                  messages_.push_back(std::move(*message));
              }
          }) {}
    ~NotifyRecorder() {
        stop_ = true;
        thread_.join();
    }
    const std::string& path() const { return socket_.path(); }
    /// The notifications containing `text` after the first RELOADING=1 and before the READY=1
    /// that follows it; nullopt while the reload has not ended so.
    std::optional<std::size_t> during_reload(const std::string& text) const {
        std::lock_guard lock(mutex_);
        std::size_t count = 0;
        bool reloading = false;
        for (const auto& message : messages_) {
            if (!reloading) {
                reloading = message.find("RELOADING=1") != std::string::npos;
            } else if (message.find("READY=1") != std::string::npos) {
                return count;
            } else {
                count += message.find(text) != std::string::npos;
            }
        }
        return std::nullopt;
    }

private:
    NotifySocket socket_;
    mutable std::mutex mutex_;
    std::vector<std::string> messages_;
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

class ReloadLargeTest : public GatewayTest {
protected:
    /// Starts the gateway with the produced exchange, `kept` and `more` exchanges, /healthz on
    /// metrics_port_; returns once datagrams are produced and /healthz answers 200.
    void start_producing(const std::string& more = "", GatewayOptions options = {}) {
        options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(metrics_port_) + "\n";
        start(produced(capture_.port()) + kept() + more, "", options);
        ASSERT_TRUE(capture_.wait_first(10s));
        // /healthz is 503 until the loop's first report, about a second after start.
        const auto deadline = ReloadClock::now() + 30s;
        while (http_get(metrics_port_, "/healthz").find(" 200 OK\r\n") == std::string::npos) {
            ASSERT_LT(ReloadClock::now(), deadline) << "/healthz never answered 200";
            std::this_thread::sleep_for(50ms);
        }
    }

    /// Sends SIGHUP and waits for the reload's first line, then for `outcome`; the produced
    /// datagrams that arrived between the two, 100 ms inside either end (the log is read every
    /// 5 ms: a datagram sent just before the first line or after the last may be recorded a
    /// little after the test saw that line).
    std::size_t reload_and_count(const std::string& outcome) {
        gateway_->signal(SIGHUP);
        EXPECT_TRUE(gateway_->wait_for_output("SIGHUP: reloading", 10s)) << gateway_->output();
        const auto started = ReloadClock::now();
        EXPECT_TRUE(gateway_->wait_for_output(outcome, 240s)) << gateway_->output();
        const auto ended = ReloadClock::now();
        const auto inside = capture_.between(started + 100ms, ended - 100ms).size();
        const auto ms = [](ReloadClock::duration d) {
            return std::chrono::duration_cast<std::chrono::milliseconds>(d).count();
        };
        std::printf(
            "reload seen for %lld ms: %zu produced datagram(s) inside it, the longest gap "
            "%lld ms\n",
            static_cast<long long>(ms(ended - started)), inside,
            static_cast<long long>(ms(capture_.longest_gap(started, ended))));
        // The gateway's own account: how long the loop applied, in how many slices.
        if (gateway_->wait_for_output("reload: parsed in", 10s)) {
            const auto out = gateway_->output();
            const auto line = out.find("reload: parsed in");
            std::printf("%s\n", out.substr(line, out.find('\n', line) - line).c_str());
        }
        return inside;
    }

    ArrivalRecorder capture_;
    std::uint16_t metrics_port_ = free_tcp_port();
};

}  // namespace eip2mqtt::test
