#include "eip2mqtt/adapters/mqtt/client.hpp"

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <mqtt/async_client.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <atomic>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/post.hpp>
#include <condition_variable>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>
#include <numeric>
#include <thread>

#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::adapters::mqtt {
namespace {

using namespace std::chrono_literals;
using test::Mosquitto;
using test::MqttRecorder;
using test::Received;

constexpr auto kTimeout = 10s;

Message msg(std::string topic, std::string payload, int qos = 1, bool retain = false,
            bool coalesce = true) {
    Message m;
    m.topic = std::move(topic);
    m.payload = std::move(payload);
    m.qos = qos;
    m.retain = retain;
    m.coalesce = coalesce;
    return m;
}

/// A Client driven by an io_context on its own thread, as the gateway drives it.
class ClientFixture : public ::testing::Test {
protected:
    ClientOptions options_for(const Mosquitto& broker) {
        ClientOptions o;
        o.url = broker.url();
        o.client_id = "client-test";
        o.availability_topic = "gw/state";
        o.min_backoff = 20ms;
        o.max_backoff = 200ms;
        return o;
    }

    void make_client(ClientOptions options) {
        client_ = std::make_unique<Client>(io_.get_executor(), std::move(options));
        client_->set_on_connected([this] {
            {
                std::lock_guard lock(mutex_);
                ++connected_count_;
            }
            cv_.notify_all();
        });
        client_->set_on_message([this](Incoming in) {
            {
                std::lock_guard lock(mutex_);
                incoming_.push_back(std::move(in));
            }
            cv_.notify_all();
        });
        loop_ = std::thread([this] { io_.run(); });
    }

    void TearDown() override {
        if (client_ && loop_.joinable()) {
            client_->stop(2s);
        }
        stop_loop();
        client_.reset();
    }

    void stop_loop() {
        work_.reset();
        io_.stop();
        if (loop_.joinable()) {
            loop_.join();
        }
    }

    /// Runs `f` on the loop and waits for it.
    template <class F>
    auto on_loop(F f) {
        std::packaged_task<decltype(f())()> task(std::move(f));
        auto result = task.get_future();
        boost::asio::post(io_, [&task] { task(); });
        EXPECT_EQ(result.wait_for(kTimeout), std::future_status::ready);
        return result.get();
    }

    bool wait_connected_count(int n) {
        std::unique_lock lock(mutex_);
        return cv_.wait_for(lock, kTimeout, [&] { return connected_count_ >= n; });
    }

    bool wait_incoming(std::size_t n) {
        std::unique_lock lock(mutex_);
        return cv_.wait_for(lock, kTimeout, [&] { return incoming_.size() >= n; });
    }

    /// Bounded polling of the client's state, which has no event of its own for "lost".
    bool wait_disconnected() {
        const auto deadline = std::chrono::steady_clock::now() + kTimeout;
        while (client_->connected()) {
            if (std::chrono::steady_clock::now() > deadline) {
                return false;
            }
            std::this_thread::sleep_for(5ms);
        }
        return true;
    }

    static std::function<bool(const std::vector<Received>&)> has_n_on(std::string topic,
                                                                      std::size_t n) {
        return [topic = std::move(topic), n](const std::vector<Received>& all) {
            std::size_t count = 0;
            for (const auto& r : all) {
                count += r.topic == topic ? 1 : 0;
            }
            return count >= n;
        };
    }

    boost::asio::io_context io_;
    std::optional<boost::asio::executor_work_guard<boost::asio::io_context::executor_type>> work_{
        io_.get_executor()};
    std::thread loop_;
    std::unique_ptr<Client> client_;

    std::mutex mutex_;
    std::condition_variable cv_;
    int connected_count_ = 0;
    std::vector<Incoming> incoming_;
};

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
    std::atomic<int> wills{0};
    options.will = [&wills] { return msg("gw/will", std::to_string(++wills), 1, false, false); };
    make_client(std::move(options));
    on_loop([&] { client_->start(); });
    ASSERT_TRUE(wait_connected_count(1));
    EXPECT_EQ(wills.load(), 1);

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
    const auto last_will = std::to_string(wills.load());
    EXPECT_GE(wills.load(), 2);
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

// Issue #12: a publication the broker refuses closes the connection; sent again after every
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

}  // namespace
}  // namespace eip2mqtt::adapters::mqtt
