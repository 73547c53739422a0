// The foreground tools' loop: it stops on SIGINT or SIGTERM, or once its duration has passed.

#include "app/cli/detail/run_until_stopped.hpp"

#include <gtest/gtest.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <csignal>

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// Keeps `loop` busy for at most 30 s, so that a loop that fails to stop fails the test
/// instead of hanging it; answers whether that timer fired.
class Watchdog {
public:
    explicit Watchdog(boost::asio::io_context& loop) : timer_(loop) {
        timer_.expires_after(30s);
        timer_.async_wait([this, &loop](const boost::system::error_code& error) {
            if (error) return;
            fired_ = true;
            loop.stop();
        });
    }
    bool fired() const { return fired_; }

private:
    boost::asio::steady_timer timer_;
    bool fired_ = false;
};

TEST(RunUntilStopped, ADurationStopsTheLoopOnceItHasPassed) {
    boost::asio::io_context loop;
    Watchdog watchdog(loop);
    const auto start = std::chrono::steady_clock::now();
    run_until_stopped(loop, 0.05);
    EXPECT_GE(std::chrono::steady_clock::now() - start, 50ms);
    EXPECT_FALSE(watchdog.fired());
}

TEST(RunUntilStopped, SigtermStopsALoopWithoutDuration) {
    boost::asio::io_context loop;
    Watchdog watchdog(loop);
    boost::asio::post(loop, [] { std::raise(SIGTERM); });
    run_until_stopped(loop, 0);
    EXPECT_FALSE(watchdog.fired());
}

TEST(RunUntilStopped, SigintStopsItBeforeItsDuration) {
    boost::asio::io_context loop;
    Watchdog watchdog(loop);
    boost::asio::post(loop, [] { std::raise(SIGINT); });
    const auto start = std::chrono::steady_clock::now();
    run_until_stopped(loop, 25);
    EXPECT_LT(std::chrono::steady_clock::now() - start, 20s);
    EXPECT_FALSE(watchdog.fired());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
