// make_role: a single unit's role fences nothing (no may_send, no session gate, sessions open at
// start, the exchanges' default options); with `redundancy:` a pair's fences what it is given,
// its sessions follow the role, and it sets the exchanges' options. The loop never runs.

#include "eip2mqtt/app/redundancy/role.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>

#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_publisher.hpp"
#include "tests/support/fakes/tag_message.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

using test::tag_message;

Role::MaySend retained_only() {
    return [](const adapters::mqtt::Message& m) { return m.retain; };
}

class RoleTest : public ::testing::Test {
protected:
    std::unique_ptr<Role> make(std::string pair) {
        config_.redundancy.pair = std::move(pair);
        return make_role(config_, loop_.get_executor(), clock_);
    }

    core::config::Config config_;
    boost::asio::io_context loop_;
    test::FakeClock clock_;
    test::RecordingPublisher publisher_;
};

TEST_F(RoleTest, ASingleUnitFencesNothingAndItsSessionsOpenAtStart) {
    auto role = make("");
    EXPECT_EQ(role->may_send(retained_only()), nullptr);
    EXPECT_EQ(role->may_send(nullptr), nullptr);
    EXPECT_EQ(role->session_gate(publisher_), nullptr);
    EXPECT_FALSE(role->sessions_follow_role());
    const auto options = role->exchanges_options();
    EXPECT_EQ(options.role, &always_leads());
    EXPECT_FALSE(options.role->hears_produced());
}

TEST_F(RoleTest, APairFencesWhatItIsGivenUntilItLeads) {
    auto role = make("turbine");
    const auto fenced = role->may_send(retained_only());
    ASSERT_NE(fenced, nullptr);
    EXPECT_TRUE(fenced(tag_message(false)));  // not fenced: passes
    EXPECT_FALSE(fenced(tag_message(true)));  // fenced, and this unit holds no lease
    const auto everything = role->may_send(nullptr);
    ASSERT_NE(everything, nullptr);
    EXPECT_FALSE(everything(tag_message(false)));
}

TEST_F(RoleTest, APairsSessionsFollowTheRoleAndItSetsTheExchangesOptions) {
    auto role = make("turbine");
    EXPECT_TRUE(role->sessions_follow_role());
    EXPECT_NE(role->session_gate(publisher_), nullptr);
    const auto options = role->exchanges_options();
    EXPECT_NE(options.role, nullptr);
    EXPECT_NE(options.role, &always_leads());
    // Its exchanges hear the datagrams the other unit produces, which a single unit's never do.
    EXPECT_TRUE(options.role->hears_produced());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
