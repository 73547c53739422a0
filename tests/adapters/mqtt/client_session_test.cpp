// The MQTT client against a real Mosquitto: acknowledgements, session-bound wills, retries,
// what it receives, MQTT 3.1.1, and publications a broker would refuse.

#include "tests/adapters/mqtt/client_fixture.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

TEST_F(ClientFixture, ReportsAckTokensOnlyOnceTheBrokerAcknowledgedAndMarksHistorical) {
    test::MosquittoOptions bo;
    bo.persistence = true;  // the recorder's session (and its queue) survives the restart
    Mosquitto broker(bo);
    MqttRecorder recorder(broker.url(), {"gw/#"}, "ack-recorder");
    std::vector<std::uint64_t> acknowledged;
    make_client(options_for(broker));
    client_->set_on_acknowledged([this, &acknowledged](std::uint64_t token) {
        {
            std::lock_guard lock(mutex_);
            acknowledged.push_back(token);
        }
        cv_.notify_all();
    });
    const auto wait_acknowledged = [&](std::size_t n) {
        std::unique_lock lock(mutex_);
        return cv_.wait_for(lock, kTimeout, [&] { return acknowledged.size() >= n; });
    };
    const auto publish_tokens = [&](std::uint64_t first, std::uint64_t last) {
        on_loop([&] {
            for (auto token = first; token <= last; ++token) {
                auto m = msg("gw/history", std::to_string(token), 1, false, false);
                m.ack_token = token;
                m.historical = token % 2 == 0;
                client_->publish(std::move(m));
            }
        });
    };
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    publish_tokens(1, 20);
    on_loop([&] { client_->publish(msg("gw/live", "no token")); });
    ASSERT_TRUE(wait_acknowledged(20));

    broker.stop();
    ASSERT_TRUE(wait_disconnected());
    publish_tokens(21, 30);
    {
        std::lock_guard lock(mutex_);
        EXPECT_EQ(acknowledged.size(), 20u);  // nothing can be acknowledged without a broker
    }
    broker.start();
    ASSERT_TRUE(wait_connected_count(2));
    ASSERT_TRUE(wait_acknowledged(30));
    ASSERT_TRUE(recorder.wait_for(has_n_on("gw/history", 30)));

    std::lock_guard lock(mutex_);
    std::vector<std::uint64_t> expected(30);
    std::iota(expected.begin(), expected.end(), 1);
    EXPECT_EQ(acknowledged, expected);  // each once, in order, and none for the untokened one
    const auto history = recorder.messages_on("gw/history");
    for (const auto& r : history) {
        const bool historical = std::stoull(r.payload) % 2 == 0;
        const std::vector<std::pair<std::string, std::string>> marked{{"historical", "true"}};
        EXPECT_EQ(r.user_properties, historical ? marked : decltype(marked){}) << r.payload;
    }
}

TEST_F(ClientFixture, ASessionBoundClientMakesAWillPerConnectAndDropsWhatAConnectionLeft) {
    test::MosquittoOptions bo;
    bo.persistence = true;  // the recorder's session (and its queue) survives the restart
    Mosquitto broker(bo);
    MqttRecorder recorder(broker.url(), {"gw/#"}, "session-recorder");
    auto options = options_for(broker);
    options.availability_topic.clear();
    options.session_bound = true;
    auto wills = std::make_shared<std::atomic<int>>(0);
    options.will = numbered_will(wills);
    make_client(std::move(options));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    EXPECT_EQ(wills->load(), 1);

    broker.stop();
    ASSERT_TRUE(wait_disconnected());
    on_loop([&] {
        for (int i = 0; i < 5; ++i) client_->publish(msg("gw/seq", "stale", 1, false, false));
    });
    EXPECT_EQ(client_->stats().queued, 0u);
    EXPECT_EQ(client_->stats().discarded, 5u);
    broker.start();
    ASSERT_TRUE(wait_connected_count(2));
    // A new will for every CONNECT sent: the one that succeeded, and any tried before the broker
    // listened again (how many depends on how fast it came back).
    const auto last_will = std::to_string(wills->load());
    EXPECT_GE(wills->load(), 2);
    on_loop([&] { client_->publish(msg("gw/seq", "fresh", 1, false, false)); });

    // A clean stop says the last will itself, after everything queued.
    client_->stop(2s);
    stop_loop();
    ASSERT_TRUE(recorder.wait_for([&](const std::vector<Received>& all) {
        return !all.empty() && all.back().topic == "gw/will" && all.back().payload == last_will;
    }));
    // (The broker may have said will 1 itself when it went down: the connection died then.)
    const auto seq = recorder.messages_on("gw/seq");
    ASSERT_EQ(seq.size(), 1u);
    EXPECT_EQ(seq[0].payload, "fresh");
    EXPECT_EQ(recorder.messages().back().payload, last_will);
}

TEST_F(ClientFixture, RetriesInitialConnectAndReconnectsAfterLoss) {
    Mosquitto broker;
    broker.stop();
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    EXPECT_FALSE(client_->connected());

    broker.start();  // the client connects on its next backoff tick
    ASSERT_TRUE(wait_connected_count(1));
    EXPECT_TRUE(client_->connected());

    MqttRecorder recorder(broker.url(), {"gw/state"});
    broker.stop();
    ASSERT_TRUE(wait_disconnected());
    broker.start();
    ASSERT_TRUE(wait_connected_count(2));  // on_connected runs again
    const auto stats = client_->stats();
    EXPECT_EQ(stats.connects, 2u);
    EXPECT_EQ(stats.connection_losses, 1u);

    // online is published again after the reconnect (the broker lost it: no persistence).
    MqttRecorder after(broker.url(), {"gw/state"});
    EXPECT_TRUE(after.wait_for_message("gw/state", [](auto& p) { return p == "online"; }));
}

/// Publishes with MQTT 5 properties, which MqttRecorder::publish does not offer.
void publish_v5(const std::string& url, const std::string& topic, const std::string& payload,
                bool retain, const std::string& response_topic = {},
                const std::string& correlation = {}, int expiry_s = 0) {
    ::mqtt::async_client cli(url, "publisher-v5", ::mqtt::create_options(MQTTVERSION_5));
    ::mqtt::connect_options co;
    co.set_mqtt_version(MQTTVERSION_5);
    co.set_clean_start(true);
    cli.connect(co)->wait();
    auto m = ::mqtt::make_message(topic, payload, 1, retain);
    ::mqtt::properties props;
    if (!response_topic.empty()) {
        props.add({::mqtt::property::RESPONSE_TOPIC, response_topic});
    }
    if (!correlation.empty()) {
        props.add({::mqtt::property::CORRELATION_DATA, correlation});
    }
    if (expiry_s > 0) {
        props.add({::mqtt::property::MESSAGE_EXPIRY_INTERVAL, expiry_s});
    }
    m->set_properties(props);
    cli.publish(m)->wait();
    cli.disconnect()->wait();
}

TEST_F(ClientFixture, ReceivesRetainedFlagAndRequestResponseProperties) {
    Mosquitto broker;
    publish_v5(broker.url(), "gw/x/set", "41", true);  // a stale retained command
    make_client(options_for(broker));
    on_loop([&] {
        client_->set_subscriptions({"gw/+/set"});
        client_->start();
    });
    ASSERT_TRUE(wait_incoming(1));
    {
        std::lock_guard lock(mutex_);
        EXPECT_EQ(incoming_[0].topic, "gw/x/set");
        EXPECT_EQ(incoming_[0].payload, "41");
        EXPECT_TRUE(incoming_[0].retained);
    }

    // no_local: our own publication on a subscribed topic does not come back.
    on_loop([&] { client_->publish(msg("gw/own/set", "0")); });
    std::string binary("\x00\x01\xff", 3);
    publish_v5(broker.url(), "gw/x/set", "42", false, "gw/reply", binary, 60);
    ASSERT_TRUE(wait_incoming(2));
    std::lock_guard lock(mutex_);
    ASSERT_EQ(incoming_.size(), 2u);
    const Incoming& live = incoming_[1];
    EXPECT_EQ(live.topic, "gw/x/set");
    EXPECT_EQ(live.payload, "42");
    EXPECT_FALSE(live.retained);
    EXPECT_EQ(live.response_topic, "gw/reply");
    EXPECT_EQ(live.correlation_data, binary);
    EXPECT_GT(live.message_expiry_s, 0);
    EXPECT_LE(live.message_expiry_s, 60);
    EXPECT_EQ(incoming_[0].message_expiry_s, -1);
    EXPECT_EQ(client_->stats().received, 2u);
}

TEST_F(ClientFixture, SubscriptionsChangedWhileConnectedTakeEffect) {
    Mosquitto broker;
    MqttRecorder probe(broker.url(), {});
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    on_loop([&] { client_->set_subscriptions({"gw/y/set"}); });
    // The subscription completes asynchronously: publish retained, which is delivered either way.
    probe.publish("gw/y/set", "7", true);
    ASSERT_TRUE(wait_incoming(1));
    std::lock_guard lock(mutex_);
    EXPECT_EQ(incoming_[0].topic, "gw/y/set");
}

TEST_F(ClientFixture, Mqtt311Works) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    recorder.publish("gw/z/set", "5", true);
    auto options = options_for(broker);
    options.version = 3;
    make_client(options);
    on_loop([&] {
        client_->set_subscriptions({"gw/+/set"});
        client_->start();
    });
    ASSERT_TRUE(wait_connected_count(1));
    ASSERT_TRUE(recorder.wait_for_message("gw/state", [](auto& p) { return p == "online"; }));
    on_loop([&] { client_->publish(msg("gw/v", "1", 0, true)); });
    EXPECT_TRUE(recorder.wait_for_message("gw/v"));
    ASSERT_TRUE(wait_incoming(1));
    std::lock_guard lock(mutex_);
    EXPECT_EQ(incoming_[0].payload, "5");
    EXPECT_TRUE(incoming_[0].retained);
}

// A publication the broker refuses closes the connection; sent again after every
// reconnect, it kept the gateway from ever staying connected.
TEST_F(ClientFixture, PublicationsABrokerWouldRefuseAreDroppedAndTheConnectionStays) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    on_loop([&] {
        client_->publish(msg("gw/#", "wildcard"));
        client_->publish(msg("gw/a\x01b", "control character"));
        client_->publish(msg("gw/\xff", "invalid UTF-8"));
        client_->publish(msg("gw/" + std::string(65533, 'l'), "too long"));
        client_->publish(msg("gw/after", "1"));
    });
    ASSERT_TRUE(recorder.wait_for_message("gw/after"));
    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.refused, 4u);
    EXPECT_EQ(stats.connects, 1u);
    EXPECT_EQ(stats.connection_losses, 0u);
}

TEST_F(ClientFixture, APublicationOverTheBrokersMaximumPacketSizeIsNeverSent) {
    Mosquitto broker(test::MosquittoOptions{.extra_config = "max_packet_size 2000\n"});
    MqttRecorder recorder(broker.url(), {"gw/#"});
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    on_loop([&] {
        client_->publish(msg("gw/big", std::string(5000, 'x')));
        client_->publish(msg("gw/after", "1"));
    });
    ASSERT_TRUE(recorder.wait_for_message("gw/after"));
    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.refused, 1u);
    EXPECT_EQ(stats.connection_losses, 0u);
}

TEST_F(ClientFixture, APublicationTheBrokerClosesTheConnectionOnIsDroppedAfterOneRetry) {
    // MQTT 3.1.1 tells the client no maximum packet size, so the publication leaves, and
    // Mosquitto closes the connection on it.
    Mosquitto broker(test::MosquittoOptions{.extra_config = "max_packet_size 2000\n"});
    MqttRecorder recorder(broker.url(), {"gw/#"});
    auto options = options_for(broker);
    options.version = 3;
    make_client(options);
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    on_loop([&] {
        client_->publish(msg("gw/before", "1"));
        client_->publish(msg("gw/big", std::string(5000, 'x')));
        client_->publish(msg("gw/after", "1"));
    });
    // Sent once with the others, once alone after the reconnect, then dropped: the
    // publications after it are delivered and the connection stays up.
    ASSERT_TRUE(recorder.wait_for_message("gw/after"));
    ASSERT_TRUE(wait_connected_count(3));
    on_loop([&] { client_->publish(msg("gw/later", "1")); });
    ASSERT_TRUE(recorder.wait_for_message("gw/later"));
    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.refused, 1u);
    EXPECT_EQ(stats.connection_losses, 2u);
    EXPECT_EQ(stats.connects, 3u);
    EXPECT_TRUE(recorder.messages_on("gw/big").empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
