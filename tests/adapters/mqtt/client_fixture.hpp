// The fixture of the MQTT client's tests against a real Mosquitto: a Client driven by an
// io_context on its own thread, as the gateway drives it, and bounded waits on its events.
#pragma once

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
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <numeric>
#include <thread>

#include "eip2mqtt/adapters/mqtt/client.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"

namespace eip2mqtt::adapters::mqtt::test_support {

using namespace std::chrono_literals;
using test::Mosquitto;
using test::MqttRecorder;
using test::Received;

constexpr auto kTimeout = 10s;

inline Message msg(std::string topic, std::string payload, int qos = 1, bool retain = false,
                   bool coalesce = true) {
    Message m;
    m.topic = std::move(topic);
    m.payload = std::move(payload);
    m.qos = qos;
    m.retain = retain;
    m.coalesce = coalesce;
    return m;
}

/// How many wills a client asked for. Shared with the will itself: the client outlives the test
/// body's locals (the fixture stops it in TearDown) and may reconnect, and ask again, in between.
using WillCount = std::shared_ptr<std::atomic<int>>;

/// A will on `topic` whose payload is its number, counted in `wills`.
inline std::function<Message()> numbered_will(WillCount wills, std::string topic = "gw/will") {
    return [wills, topic] { return msg(topic, std::to_string(++*wills), 1, false, false); };
}

/// How many of `all` are on `topic` with `payload`.
inline std::size_t count_on(const std::vector<Received>& all, const std::string& topic,
                            const std::string& payload) {
    std::size_t count = 0;
    for (const auto& r : all) count += r.topic == topic && r.payload == payload ? 1 : 0;
    return count;
}

/// A Client driven by an io_context on its own thread, as the gateway drives it.
class ClientFixture : public ::testing::Test {
protected:
    ClientOptions options_for(const Mosquitto& broker) {
        ClientOptions o;
        o.urls = {broker.url()};
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

    /// Makes the client on `options`, connecting through a proxy on 127.0.0.1:`proxy_port`,
    /// and starts it; true once it connected.
    bool start_through(ClientOptions options, std::uint16_t proxy_port) {
        options.urls = {"tcp://127.0.0.1:" + std::to_string(proxy_port)};
        make_client(std::move(options));
        on_loop([&] { client_->start(); });
        return wait_connected_count(1);
    }

    /// Publishes "0", "1", ... on `topic` (QoS 1), `count` of them, from the loop.
    void publish_numbered(const std::string& topic, std::size_t count) {
        on_loop([&] {
            for (std::size_t i = 0; i < count; ++i) {
                client_->publish(msg(topic, std::to_string(i), 1, false, false));
            }
        });
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

}  // namespace eip2mqtt::adapters::mqtt::test_support
