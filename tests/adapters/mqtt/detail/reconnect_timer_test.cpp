// ReconnectTimer: the backoff's delays, asked at the client's clock's time (a fake here: the
// outage's age caps the doubling), and the timer that runs them out on the loop.

#include "adapters/mqtt/detail/reconnect_timer.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <memory>

#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

TEST(ReconnectTimer, TheOutagesAgeOnTheClockCapsTheDoubling) {
    boost::asio::io_context io;
    LoopPost loop(io.get_executor());
    test::FakeClock clock;
    ClientOptions options;
    options.min_backoff = 250ms;
    options.max_backoff = 30s;
    options.clock = &clock;
    ReconnectTimer timer(loop, options);
    EXPECT_EQ(timer.schedule([] {}), 250ms);
    clock.advance(8s);  // cap: 8 s / 4
    EXPECT_EQ(timer.schedule([] {}), 500ms);
    EXPECT_EQ(timer.schedule([] {}), 1000ms);
    EXPECT_EQ(timer.schedule([] {}), 2000ms);
    EXPECT_EQ(timer.schedule([] {}), 2000ms);
    timer.reset();
    EXPECT_EQ(timer.schedule([] {}), 250ms);
    timer.cancel();
}

TEST(ReconnectTimer, RunsOnDueOnTheLoopUnlessCancelled) {
    boost::asio::io_context io;
    LoopPost loop(io.get_executor());
    auto owner = std::make_shared<int>(0);
    loop.bind(owner);
    ClientOptions options;
    options.min_backoff = 1ms;
    options.max_backoff = 1ms;
    ReconnectTimer timer(loop, options);
    int due = 0;
    timer.schedule([&] { ++due; });
    io.run();
    EXPECT_EQ(due, 1);
    timer.schedule([&] { ++due; });
    timer.cancel();
    io.restart();
    io.run();
    EXPECT_EQ(due, 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
