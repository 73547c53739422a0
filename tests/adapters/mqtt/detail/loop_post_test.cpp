// Work posted for the client runs on the loop only while the client lives.

#include "adapters/mqtt/detail/loop_post.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/steady_timer.hpp>
#include <memory>

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(LoopPost, RunsPostedWorkOnTheLoopWhileTheOwnerLives) {
    boost::asio::io_context io;
    LoopPost loop(io.get_executor());
    auto owner = std::make_shared<int>(0);
    loop.bind(owner);
    int runs = 0;
    loop.post([&] { ++runs; });
    EXPECT_EQ(runs, 0);  // not on the posting thread's stack
    io.run();
    EXPECT_EQ(runs, 1);
}

TEST(LoopPost, DropsWorkWhoseOwnerIsGone) {
    boost::asio::io_context io;
    LoopPost loop(io.get_executor());
    auto owner = std::make_shared<int>(0);
    loop.bind(owner);
    int runs = 0;
    loop.post([&] { ++runs; });
    owner.reset();
    io.run();
    EXPECT_EQ(runs, 0);
}

TEST(LoopPost, KeepsTheOwnerAliveWhileItsWorkRuns) {
    boost::asio::io_context io;
    LoopPost loop(io.get_executor());
    auto owner = std::make_shared<int>(0);
    std::weak_ptr<int> watch = owner;
    loop.bind(owner);
    bool alive_inside = false;
    loop.post([&] {
        owner.reset();  // the last outside reference goes while the work runs
        alive_inside = !watch.expired();
    });
    io.run();
    EXPECT_TRUE(alive_inside);
    EXPECT_TRUE(watch.expired());
}

TEST(LoopPost, GuardsATimersHandlerAndPassesItsArguments) {
    boost::asio::io_context io;
    LoopPost loop(io.get_executor());
    auto owner = std::make_shared<int>(0);
    loop.bind(owner);
    boost::asio::steady_timer kept(io);
    boost::asio::steady_timer orphaned(io);
    int fired = 0;
    boost::system::error_code seen = boost::asio::error::operation_aborted;
    kept.expires_after(std::chrono::milliseconds(0));
    kept.async_wait(loop.guarded([&](const boost::system::error_code& ec) {
        ++fired;
        seen = ec;
    }));
    io.run();
    EXPECT_EQ(fired, 1);
    EXPECT_FALSE(seen);

    io.restart();
    orphaned.expires_after(std::chrono::milliseconds(0));
    orphaned.async_wait(loop.guarded([&](const boost::system::error_code&) { ++fired; }));
    owner.reset();
    io.run();
    EXPECT_EQ(fired, 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
