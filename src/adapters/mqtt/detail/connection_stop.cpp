// The Connection's part in stop(), on the stopping thread (the loop may no longer run), and
// its counters.

#include <spdlog/spdlog.h>

#include <utility>

#include "adapters/mqtt/detail/connection.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

void Connection::add_stats(ClientStats& stats) const {
    stats.connected = connected_;
    // The list never changes and broker_ only names one of it: safe off the loop.
    if (stats.connected) stats.broker = options_.urls[broker_];
    stats.connects = connects_;
    stats.connection_losses = connection_losses_;
    stats.received = received_;
}

void Connection::on_stopped() {
    state_ = State::stopped;
    connected_ = false;
    reconnect_timer_.cancel();
}

bool Connection::link_alive() const { return sender_.link_up() && paho_.is_connected(); }

paho::delivery_token_ptr Connection::publish_last_will() {
    std::optional<Message> will;
    {
        std::lock_guard lock(will_mutex_);
        will = std::exchange(last_will_, std::nullopt);
    }
    if (!will) {
        return nullptr;
    }
    try {
        return paho_.publish(
            paho::make_message(will->topic, will->payload, will->qos, will->retain));
    } catch (const paho::exception& e) {
        spdlog::warn("{} cannot publish the will on {}: {}", options_.log_name, will->topic,
                     e.what());
    }
    return nullptr;
}

paho::delivery_token_ptr Connection::publish_offline(Clock::time_point deadline) {
    if (options_.availability_topic.empty()) {
        return nullptr;
    }
    std::uint64_t generation = 0;
    if (options_.availability_qos > 0) {
        // Its slot first, so that the sender takes no freed one; then wait until the window
        // has room for it, or Paho would hold it until its next one-second cycle.
        generation = sender_.reserve_own_slot();
        sender_.wait_for_own_slots(deadline);
    }
    try {
        return sender_.publish_own(paho::make_message(options_.availability_topic, "offline",
                                                      options_.availability_qos, true),
                                   generation);
    } catch (const paho::exception& e) {
        spdlog::warn("{} cannot publish availability: {}", options_.log_name, e.what());
    }
    return nullptr;
}

void Connection::disconnect() {
    try {
        paho_.disconnect(paho::disconnect_options(std::chrono::seconds(1)))
            ->wait_for(std::chrono::seconds(2));
    } catch (const paho::exception& e) {
        spdlog::warn("{} disconnect failed: {}", options_.log_name, e.what());
    }
    sender_.set_link_up(false);
    connected_ = false;
    spdlog::info("{} disconnected from {}", options_.log_name, url());
}

}  // namespace eip2mqtt::adapters::mqtt::detail
