// The MQTT client against a real Mosquitto: connecting, publishing, the will, and its queue
// while the broker is away.

#include "tests/adapters/mqtt/client_fixture.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace EIP2MQTT_THIS_FILE {

using namespace test_support;

TEST_F(ClientFixture, ConnectsPublishesRetainedAndAnnouncesOnline) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));

    auto online = recorder.wait_for_message("gw/state", [](auto& p) { return p == "online"; });
    ASSERT_TRUE(online);
    EXPECT_TRUE(online->retained);

    on_loop([&] { client_->publish(msg("gw/a", "1", 1, true)); });
    auto a = recorder.wait_for_message("gw/a");
    ASSERT_TRUE(a);
    EXPECT_EQ(a->payload, "1");
    EXPECT_TRUE(a->retained);

    // A late subscriber gets both retained.
    MqttRecorder late(broker.url(), {"gw/#"});
    EXPECT_TRUE(late.wait_for_message("gw/a"));
    EXPECT_TRUE(late.wait_for_message("gw/state", [](auto& p) { return p == "online"; }));

    const auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_TRUE(stats.connected);
    EXPECT_EQ(stats.connects, 1u);
    EXPECT_GE(stats.published, 1u);
    EXPECT_EQ(stats.publish_failures, 0u);
}

TEST_F(ClientFixture, StopAfterLoopEndedFlushesQueueThenPublishesOffline) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));

    // Queue while the loop is busy, then end the loop before it can pump them.
    constexpr int kCount = 200;
    boost::asio::post(io_, [&] {
        for (int i = 0; i < kCount; ++i) {
            client_->publish(msg("gw/seq", std::to_string(i), 1, false, false));
        }
        io_.stop();
    });
    loop_.join();

    client_->stop(5s);
    ASSERT_TRUE(recorder.wait_for(has_n_on("gw/seq", kCount)));
    const auto seq = recorder.messages_on("gw/seq");
    for (int i = 0; i < kCount; ++i) {
        EXPECT_EQ(seq[i].payload, std::to_string(i));
    }
    auto offline = recorder.wait_for_message("gw/state", [](auto& p) { return p == "offline"; });
    ASSERT_TRUE(offline);
    EXPECT_TRUE(offline->retained);
    EXPECT_EQ(client_->stats().published, static_cast<std::uint64_t>(kCount));
    EXPECT_FALSE(client_->connected());
}

/// This process's TCP sockets connected to 127.0.0.1:`port`.
std::vector<int> sockets_to(std::uint16_t port) {
    std::vector<int> fds;
    for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd")) {
        const int fd = std::atoi(entry.path().filename().c_str());
        sockaddr_in peer{};
        socklen_t len = sizeof peer;
        if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &len) == 0 &&
            peer.sin_family == AF_INET && ntohs(peer.sin_port) == port) {
            fds.push_back(fd);
        }
    }
    return fds;
}

TEST_F(ClientFixture, CutConnectionFiresWillThenReconnectsOnline) {
    Mosquitto broker;
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    const auto client_sockets = sockets_to(broker.port());  // before the recorder connects
    ASSERT_EQ(client_sockets.size(), 1u);
    int nodelay = 0;
    socklen_t len = sizeof nodelay;
    ASSERT_EQ(::getsockopt(client_sockets[0], IPPROTO_TCP, TCP_NODELAY, &nodelay, &len), 0);
    EXPECT_NE(nodelay, 0);  // detail/tcp_nodelay.hpp

    MqttRecorder recorder(broker.url(), {"gw/state"});
    ASSERT_TRUE(recorder.wait_for_message("gw/state", [](auto& p) { return p == "online"; }));
    const auto from = recorder.count();

    // No DISCONNECT: the broker publishes the will; the client reconnects.
    ::shutdown(client_sockets[0], SHUT_RDWR);
    auto offline = recorder.wait_for_message(
        "gw/state", [](auto& p) { return p == "offline"; }, kTimeout, from);
    ASSERT_TRUE(offline);
    EXPECT_TRUE(offline->retained);
    ASSERT_TRUE(wait_connected_count(2));
    EXPECT_TRUE(recorder.wait_for_message(
        "gw/state", [](auto& p) { return p == "online"; }, kTimeout, from + 1));
    EXPECT_EQ(client_->stats().connection_losses, 1u);
}

TEST_F(ClientFixture, CoalescesAndDropsOldestWhileNotConnected) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    make_client(options_for(broker));

    on_loop([&] {
        client_->set_buffer_capacity(5);
        client_->publish(msg("gw/a", "1"));
        client_->publish(msg("gw/a", "2"));
        client_->publish(msg("gw/a", "3"));  // replaces 1 then 2
        for (int i = 0; i < 10; ++i) {       // 11 queued in all: 6 oldest dropped
            client_->publish(msg("gw/seq", std::to_string(i), 1, false, false));
        }
    });
    auto stats = on_loop([&] { return client_->stats(); });
    EXPECT_EQ(stats.coalesced, 2u);
    EXPECT_EQ(stats.dropped_overflow, 6u);
    EXPECT_EQ(stats.queued, 5u);

    on_loop([&] { client_->start(); });
    ASSERT_TRUE(recorder.wait_for(has_n_on("gw/seq", 5)));
    const auto seq = recorder.messages_on("gw/seq");
    ASSERT_EQ(seq.size(), 5u);
    for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(seq[i].payload, std::to_string(i + 5));
    }
    EXPECT_TRUE(recorder.messages_on("gw/a").empty());  // dropped with the oldest
}

TEST_F(ClientFixture, LatestValueWinsPerTopicWhileQueued) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    make_client(options_for(broker));
    on_loop([&] {
        for (int i = 0; i < 5; ++i) {
            client_->publish(msg("gw/a", "a" + std::to_string(i)));
            client_->publish(msg("gw/b", "b" + std::to_string(i)));
        }
        client_->start();
    });
    ASSERT_TRUE(recorder.wait_for_message("gw/b", [](auto& p) { return p == "b4"; }));
    const auto a = recorder.messages_on("gw/a");
    ASSERT_EQ(a.size(), 1u);
    EXPECT_EQ(a[0].payload, "a4");
    EXPECT_EQ(recorder.messages_on("gw/b").size(), 1u);
    EXPECT_EQ(client_->stats().coalesced, 8u);
}

TEST_F(ClientFixture, BatchLaneIsServedInTurnWithTheMainQueueAndBounded) {
    Mosquitto broker;
    MqttRecorder recorder(broker.url(), {"gw/#"});
    auto options = options_for(broker);
    options.availability_topic.clear();
    options.batch_lane_max_messages = 3;
    make_client(options);
    on_loop([&] {
        for (int i = 0; i < 5; ++i) {
            client_->publish(msg("gw/t/" + std::to_string(i), "t" + std::to_string(i)));
        }
        for (int i = 0; i < 4; ++i) {  // the first is dropped: the lane holds 3
            auto m = msg("gw/_values", "v" + std::to_string(i), 1, false, false);
            m.batch_lane = true;
            client_->publish(std::move(m));
        }
    });
    EXPECT_EQ(client_->stats().dropped_overflow, 1u);
    EXPECT_EQ(client_->stats().queued, 8u);
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(
        recorder.wait_for([](const std::vector<Received>& all) { return all.size() >= 8; }));
    std::vector<std::string> order;
    for (const auto& r : recorder.messages()) order.push_back(r.payload);
    // One connection, QoS 1: the broker forwards in the order the client took them.
    EXPECT_EQ(order, (std::vector<std::string>{"t0", "v1", "t1", "v2", "t2", "v3", "t3", "t4"}));
}

TEST_F(ClientFixture, BuffersWhileBrokerIsDownAndDeliversInOrder) {
    test::MosquittoOptions bo;
    bo.persistence = true;  // the recorder's session (and its queue) survives the restart
    Mosquitto broker(bo);
    MqttRecorder recorder(broker.url(), {"gw/seq"}, "buffer-recorder");
    make_client(options_for(broker));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));

    broker.stop();
    ASSERT_TRUE(wait_disconnected());
    constexpr int kCount = 50;
    on_loop([&] {
        for (int i = 0; i < kCount; ++i) {
            client_->publish(msg("gw/seq", std::to_string(i), 1, false, false));
        }
    });
    EXPECT_EQ(client_->stats().queued, static_cast<std::uint64_t>(kCount));
    broker.start();

    ASSERT_TRUE(wait_connected_count(2));
    ASSERT_TRUE(recorder.wait_for(has_n_on("gw/seq", kCount)));
    const auto seq = recorder.messages_on("gw/seq");
    for (int i = 0; i < kCount; ++i) {
        EXPECT_EQ(seq[i].payload, std::to_string(i));
    }
    const auto stats = client_->stats();
    EXPECT_EQ(stats.connection_losses, 1u);
    EXPECT_EQ(stats.connects, 2u);
    EXPECT_EQ(stats.dropped_overflow, 0u);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt
