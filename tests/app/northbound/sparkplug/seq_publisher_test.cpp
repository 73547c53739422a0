// The edge node's publications alone: seq counts only what was published, a message over the
// largest packet the broker takes (or max_packet_bytes) never leaves, and each carries the
// QoS 0, retain off, the time and the ack_token it is given.

#include "eip2mqtt/app/northbound/sparkplug/seq_publisher.hpp"

#include <gtest/gtest.h>

#include <string>

#include "sparkplug_b.pb.h"
#include "tests/support/fakes/fake_clock.hpp"
#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace EIP2MQTT_THIS_FILE {

using adapters::sparkplug::DataType;
using adapters::sparkplug::Payload;

constexpr std::int64_t now_ms = 1700000000000;

/// A payload of one string metric of `bytes` characters.
Payload of_size(std::size_t bytes) {
    Payload payload;
    payload.metrics.push_back(
        {"s", std::nullopt, 0, DataType::string, std::string(bytes, 'x'), false, {}});
    return payload;
}

std::uint64_t seq_of(const adapters::mqtt::Message& message) {
    org::eclipse::tahu::protobuf::Payload proto;
    EXPECT_TRUE(proto.ParseFromString(message.payload));
    return proto.seq();
}

class SeqPublisherTest : public ::testing::Test {
protected:
    test::RecordingPublisher mqtt_;
    test::FakeClock clock_{core::WallTime{std::chrono::milliseconds(now_ms)}};
};

TEST_F(SeqPublisherTest, SeqCountsOnlyWhatWasPublished) {
    SeqPublisher out(mqtt_, clock_, 0);
    out.connected(1000);
    auto small = of_size(10);
    auto large = of_size(2000);
    EXPECT_TRUE(out.publish("t/a", small));
    EXPECT_FALSE(out.publish("t/b", large));
    EXPECT_GT(out.last_packet_bytes(), 1000u);
    EXPECT_TRUE(out.publish("t/c", small, 42));
    ASSERT_EQ(mqtt_.published.size(), 2u);
    EXPECT_EQ(seq_of(mqtt_.published[0]), 0u);
    EXPECT_EQ(seq_of(mqtt_.published[1]), 1u);
    EXPECT_EQ(mqtt_.published[1].topic, "t/c");
    EXPECT_EQ(mqtt_.published[1].qos, 0);  // Sparkplug B 3.0: births and data at QoS 0
    EXPECT_FALSE(mqtt_.published[1].retain);
    EXPECT_EQ(mqtt_.published[1].ack_token, 42u);
    EXPECT_FALSE(mqtt_.published[1].coalesce);
    EXPECT_EQ(small.timestamp_ms, static_cast<std::uint64_t>(now_ms));
    out.restart_seq();
    EXPECT_TRUE(out.publish("t/d", small));
    EXPECT_EQ(seq_of(mqtt_.published[2]), 0u);
}

TEST_F(SeqPublisherTest, SeqRunsTo255ThenStartsAgain) {
    SeqPublisher out(mqtt_, clock_, 0);
    out.connected(adapters::mqtt::max_mqtt_packet_bytes);
    auto payload = of_size(1);
    for (int i = 0; i < 257; ++i) ASSERT_TRUE(out.publish("t", payload));
    EXPECT_EQ(seq_of(mqtt_.published[255]), 255u);
    EXPECT_EQ(seq_of(mqtt_.published[256]), 0u);
}

TEST_F(SeqPublisherTest, TheConfiguredLimitLowersTheBrokersAndNeverRaisesIt) {
    SeqPublisher configured(mqtt_, clock_, 500);
    configured.connected(1000);
    EXPECT_EQ(configured.max_packet_bytes(), 500u);
    EXPECT_TRUE(configured.limit_configured());
    configured.connected(300);
    EXPECT_EQ(configured.max_packet_bytes(), 300u);
    SeqPublisher unconfigured(mqtt_, clock_, 0);
    unconfigured.connected(1000);
    EXPECT_EQ(unconfigured.max_packet_bytes(), 1000u);
    EXPECT_FALSE(unconfigured.limit_configured());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::northbound::sparkplug
