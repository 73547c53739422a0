// The pair's own logic outside its parts: the fence its connections' sender threads ask
// (Pair::may_send). Its parts are tested on their own (pair_lease_test, pair_images_test,
// pair_writes_test, pair_history_test), the pair's role changes against a fake broker
// (pair_role_test) and end to end (tests/integration/*hot_standby*).

#include "eip2mqtt/app/redundancy/pair.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/tag_message.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using test::tag_message;

class PairTest : public ::testing::Test {
protected:
    boost::asio::io_context loop_;
    test::FakeClock clock_;
    Pair pair_{loop_.get_executor(), clock_};
};

TEST_F(PairTest, BeforeItLeadsNothingOnlyALeaderSaysPasses) {
    const auto every = pair_.may_send(nullptr);
    EXPECT_FALSE(every(tag_message(false)));
    EXPECT_FALSE(every(tag_message(true)));
}

TEST_F(PairTest, WhatALeaderAloneSaysIsFencedTheRestPasses) {
    // As the JSON tree's connection: its retained values are the leader's, the rest both units'.
    const auto retained_only =
        pair_.may_send([](const adapters::mqtt::Message& m) { return m.retain; });
    EXPECT_TRUE(retained_only(tag_message(false)));
    EXPECT_FALSE(retained_only(tag_message(true)));
    clock_.advance(std::chrono::hours(24 * 365));  // no time opens the fence: only a lease
    EXPECT_FALSE(retained_only(tag_message(true)));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
