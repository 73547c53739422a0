// The datagram router of a pair's standby: a datagram of an exchange this unit produces (the
// leader's, heard on a multicast group or broadcast both units receive) sets the request id its
// own producer sends next, while the standby follows; it is never counted as dropped. Without a
// pair such datagrams stay unknown ones. The producer is real, on a temporary state directory;
// the loop never runs.

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/asio/io_context.hpp>
#include <chrono>
#include <filesystem>

#include "eip2mqtt/adapters/state/image_store.hpp"
#include "eip2mqtt/app/exchanges/datagram_router.hpp"
#include "tests/app/support/producer_rig.hpp"
#include "tests/app/support/test_plan.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/fakes/recording_northbound.hpp"
#include "tests/support/fakes/switched_role.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using core::wire::DropReason;

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t rid) {
    return test::DatagramBuilder("10.0.0.1", exchange_id, 4).request_id(rid).build();
}

class DatagramRouterFollowedTest : public ::testing::Test {
protected:
    void SetUp() override {
        producers_.push_back(rig_.make(test::test_produced_plan(), northbound_));
    }
    void TearDown() override { producers_.clear(); }
    void route(std::uint32_t exchange_id, std::uint16_t rid) {
        now_ += 10ms;
        router_.route(datagram(exchange_id, rid), {0x0A000002, 18246}, false, now_);
    }
    std::uint16_t next_id() const { return producers_.front()->image().next_request_id(); }

    test::ProducerRig rig_{"eip2mqtt_router_followed"};
    test::RecordingNorthbound northbound_;
    std::vector<std::unique_ptr<ExchangeProducer>> producers_;
    DatagramRouter router_;
    test::SwitchedRole role_;
    core::MonoTime now_ = core::MonoTime{} + 1h;
};

TEST_F(DatagramRouterFollowedTest, AStandbyContinuesAfterTheLastRequestIdItHeard) {
    role_.leading = false;  // a standby: it follows
    router_.set_followed(producers_, role_);
    route(10, 500);
    route(10, 501);
    EXPECT_EQ(next_id(), 502);
    // Wrapping, as the leader's ids do.
    route(10, 65535);
    EXPECT_EQ(next_id(), 0);
    EXPECT_EQ(router_.counters().produced_heard, 3u);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 0u);
    EXPECT_EQ(router_.counters().accepted, 0u);
    // Another exchange of the same producer id is no one's.
    route(11, 7);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 1u);
    EXPECT_EQ(next_id(), 0);
}

TEST_F(DatagramRouterFollowedTest, ALeaderHearingItsOwnDatagramsKeepsItsIds) {
    role_.leading = true;  // it does not follow
    router_.set_followed(producers_, role_);
    const auto own = next_id();
    route(10, 900);
    EXPECT_EQ(next_id(), own);
    EXPECT_EQ(router_.counters().produced_heard, 1u);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 0u);
    role_.leading = false;
    route(10, 901);
    EXPECT_EQ(next_id(), 902);
}

TEST_F(DatagramRouterFollowedTest, WithoutAPairAProducedExchangeHeardIsUnknown) {
    router_.set_followed(producers_, app::redundancy::always_leads());
    const auto own = next_id();
    route(10, 900);
    EXPECT_EQ(next_id(), own);
    EXPECT_EQ(router_.counters().produced_heard, 0u);
    EXPECT_EQ(router_.counters().dropped_for(DropReason::unknown_exchange), 1u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
