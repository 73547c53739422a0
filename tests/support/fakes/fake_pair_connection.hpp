#pragma once
// A fake broker behind a pair's connection (app/redundancy/pair_connection.hpp): it keeps what
// the pair publishes and subscribes to, and the test plays the broker's part by hand: the
// CONNACK (connect()), a message heard (deliver()), the PUBACK of a publication (acknowledge()).
// Nothing is sent and nothing happens unless the test says so. One thread.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/app/redundancy/pair_connection.hpp"

namespace eip2mqtt::test {

class FakePairConnection final : public app::redundancy::PairConnection {
public:
    void publish(adapters::mqtt::Message&& message) override {
        published.push_back(std::move(message));
        message.clear();
    }
    void set_subscriptions(std::vector<std::string> filters) override {
        subscriptions = std::move(filters);
    }
    void set_on_connected(Connected handler) override { on_connected_ = std::move(handler); }
    void set_on_message(Heard handler) override { on_message_ = std::move(handler); }
    void set_on_acknowledged(Acknowledged handler) override {
        on_acknowledged_ = std::move(handler);
    }
    void start() override { started = true; }
    void stop(std::chrono::milliseconds flush_timeout) override { stopped = flush_timeout; }
    bool connected() const override { return up; }

    /// The broker accepted the connection: the pair's handler runs.
    void connect() {
        up = true;
        if (on_connected_) on_connected_();
    }
    /// The broker hands the pair `message` (one of its subscriptions').
    void deliver(adapters::mqtt::Incoming message) {
        if (on_message_) on_message_(std::move(message));
    }
    /// The broker acknowledged the publication that carried `token`.
    void acknowledge(std::uint64_t token) {
        if (on_acknowledged_) on_acknowledged_(token);
    }

    /// The payloads published on `topic`, in order.
    std::vector<std::string> on(const std::string& topic) const {
        std::vector<std::string> payloads;
        for (const auto& m : published) {
            if (m.topic == topic) payloads.push_back(m.payload);
        }
        return payloads;
    }
    /// The publications on topics that start with `prefix`.
    std::size_t count_under(const std::string& prefix) const {
        std::size_t count = 0;
        for (const auto& m : published) count += m.topic.rfind(prefix, 0) == 0 ? 1 : 0;
        return count;
    }

    std::vector<adapters::mqtt::Message> published;
    std::vector<std::string> subscriptions;
    bool started = false;
    bool up = false;
    std::optional<std::chrono::milliseconds> stopped;  ///< stop()'s flush timeout

private:
    Connected on_connected_;
    Heard on_message_;
    Acknowledged on_acknowledged_;
};

}  // namespace eip2mqtt::test
