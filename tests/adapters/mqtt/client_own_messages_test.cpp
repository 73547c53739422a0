// ClientOptions::hear_own and retain_as_published against a real Mosquitto: a pair's
// connection hears its own publications, and tells one sent back live (retain flag off) from
// one its subscription fetched from the broker's store (retain flag on).

#include <algorithm>
#include <string>

#include "tests/adapters/mqtt/client_fixture.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

class OwnMessagesTest : public ClientFixture {
protected:
    /// Starts a client that hears its own, subscribed to gw/own/#, and publishes a retained
    /// message there; returns the message it heard back.
    Incoming heard_back(bool retain_as_published) {
        auto options = options_for(broker_);
        options.hear_own = true;
        options.retain_as_published = retain_as_published;
        make_client(std::move(options));
        on_loop([&] {
            client_->set_subscriptions({"gw/own/#"});
            client_->start();
        });
        EXPECT_TRUE(wait_connected_count(1));
        // The subscription is made once connected, and a publication may pass before it: a
        // probe, not retained, goes until one is heard (bounded), then the retained message.
        std::size_t probes = 0;
        while (probes < 100) {
            on_loop([&] { client_->publish(msg("gw/own/probe", "p", 1, false, false)); });
            ++probes;
            if (wait_incoming_for(1, 100ms)) break;
        }
        std::size_t heard = 0;
        {
            std::lock_guard lock(mutex_);
            heard = incoming_.size();
        }
        on_loop([&] { client_->publish(msg("gw/own/image", "1", 1, true)); });
        std::unique_lock lock(mutex_);
        const auto image = [&] {
            return std::find_if(incoming_.begin(), incoming_.end(),
                                [](const Incoming& in) { return in.topic == "gw/own/image"; });
        };
        EXPECT_TRUE(cv_.wait_for(lock, kTimeout, [&] { return image() != incoming_.end(); }))
            << "probes heard: " << heard << " of " << probes;
        return image() != incoming_.end() ? *image() : Incoming{};
    }

    bool wait_incoming_for(std::size_t n, std::chrono::milliseconds within) {
        std::unique_lock lock(mutex_);
        return cv_.wait_for(lock, within, [&] { return incoming_.size() >= n; });
    }

    Mosquitto broker_;
};

TEST_F(OwnMessagesTest, WithoutRetainAsPublishedItsOwnRetainedMessageComesBackLive) {
    const auto live = heard_back(false);
    EXPECT_EQ(live.topic, "gw/own/image");
    EXPECT_FALSE(live.retained);
    // A later subscription fetches the stored copy: that one says retained.
    MqttRecorder late(broker_.url(), {"gw/own/#"}, "own-late");
    ASSERT_TRUE(late.wait_for_message("gw/own/image", [](auto& p) { return p == "1"; }));
    EXPECT_TRUE(late.messages_on("gw/own/image").front().retained);
}

TEST_F(OwnMessagesTest, WithRetainAsPublishedTheLiveCopyKeepsItsFlag) {
    EXPECT_TRUE(heard_back(true).retained);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
