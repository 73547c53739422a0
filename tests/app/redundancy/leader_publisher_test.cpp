// The Sparkplug node's publications in a pair pass only while the unit leads.

#include "eip2mqtt/app/redundancy/leader_publisher.hpp"

#include <gtest/gtest.h>

#include "tests/support/fakes/recording_publisher.hpp"

namespace eip2mqtt::app::redundancy {
namespace EIP2MQTT_THIS_FILE {

adapters::mqtt::Message message(std::string topic) {
    adapters::mqtt::Message m;
    m.topic = std::move(topic);
    m.payload = "x";
    return m;
}

TEST(LeaderPublisher, PublicationsPassWhileTheUnitLeadsAndAreDroppedOtherwise) {
    test::RecordingPublisher inner;
    bool leading = true;
    LeaderPublisher publisher(inner, [&leading] { return leading; });
    publisher.publish(message("spBv1.0/g/NDATA/n"));
    leading = false;
    auto dropped = message("spBv1.0/g/NBIRTH/n");
    publisher.publish(std::move(dropped));
    EXPECT_TRUE(dropped.topic.empty());  // left blank, as the client leaves it
    leading = true;
    publisher.publish(message("spBv1.0/g/DDATA/n/d"));
    EXPECT_EQ(inner.published.size(), 2u);
    EXPECT_EQ(inner.published[0].topic, "spBv1.0/g/NDATA/n");
    EXPECT_EQ(inner.published[1].topic, "spBv1.0/g/DDATA/n/d");
}

TEST(LeaderPublisher, SubscriptionsGoToTheConnectionWhateverTheRole) {
    test::RecordingPublisher inner;
    LeaderPublisher publisher(inner, [] { return false; });
    publisher.set_subscriptions({"spBv1.0/g/NCMD/n"});
    EXPECT_EQ(inner.subscriptions, std::vector<std::string>{"spBv1.0/g/NCMD/n"});
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::redundancy
