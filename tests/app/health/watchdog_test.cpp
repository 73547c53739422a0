// systemd's watchdog: pinged from the loop at half WatchdogSec while it runs, never when
// systemd asked for none, and no more once stopped.

#include "eip2mqtt/app/health/watchdog.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>

#include "tests/support/notify_socket.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// NOTIFY_SOCKET (and WATCHDOG_USEC when `watchdog_usec` is not empty) set for one test.
class SystemdEnvironment {
public:
    SystemdEnvironment(const std::string& socket, const std::string& watchdog_usec) {
        ::setenv("NOTIFY_SOCKET", socket.c_str(), 1);
        if (!watchdog_usec.empty()) ::setenv("WATCHDOG_USEC", watchdog_usec.c_str(), 1);
    }
    ~SystemdEnvironment() {
        ::unsetenv("NOTIFY_SOCKET");
        ::unsetenv("WATCHDOG_USEC");
    }
};

std::string socket_path() {
    return (std::filesystem::temp_directory_path() /
            ("eip2mqtt-watchdog-" + std::to_string(::getpid()) + ".sock"))
        .string();
}

/// Runs a watchdog on a loop of its own thread while `body` runs, then stops both.
template <class Body>
void with_running_watchdog(Body body) {
    boost::asio::io_context loop;
    auto work = boost::asio::make_work_guard(loop);
    adapters::systemd::Notifier notifier;
    Watchdog watchdog(loop.get_executor(), notifier);
    watchdog.start(core::MonoTime{});
    std::thread runner([&] { loop.run_for(60s); });
    body();
    boost::asio::post(loop, [&] {
        watchdog.stop();
        work.reset();
    });
    runner.join();
}

TEST(Watchdog, PingsWhileTheLoopRuns) {
    test::NotifySocket socket(socket_path());
    SystemdEnvironment environment(socket.path(), "40000");  // pings every 20 ms
    with_running_watchdog([&] {
        for (int i = 0; i < 3; ++i) EXPECT_TRUE(socket.wait_for("WATCHDOG=1", 10s)) << i;
    });
}

TEST(Watchdog, SaysNothingWithoutWatchdogSec) {
    test::NotifySocket socket(socket_path());
    SystemdEnvironment environment(socket.path(), "");
    // The loop runs dry once the watchdog is stopped: nothing was scheduled, nothing said.
    with_running_watchdog([] {});
    EXPECT_FALSE(socket.receive(0ms).has_value());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
