// The Connection's way down: failed attempts, lost connections, the reconnect, a session ended
// on purpose, and its part in stop() (on the stopping thread: the loop may no longer run).

#include <spdlog/spdlog.h>

#include <utility>

#include "adapters/mqtt/detail/connection.hpp"
#include "adapters/mqtt/detail/publish_properties.hpp"

namespace mqtt {

// Paho C++ 1.2.0 fills its disconnect options as version 0 of Paho C's structure, which Paho C
// reads without a reason code (MQTTAsync_disconnect1 takes it from version 1 on), and has no
// setter for the version: a reason set is never sent. The class it names a friend for its own
// tests is the one way to the field.
class disconnect_options_test {
public:
    static void send_reason_code(disconnect_options& options) { options.opts_.struct_version = 1; }
};

}  // namespace mqtt

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

// --- failing and losing --------------------------------------------------------------------

void Connection::on_connect_failed(std::string reason, int return_code) {
    reason = diagnosis_.explain_connect_failure(std::move(reason), return_code, connect_token_,
                                                brokers_.endpoint());
    if (const auto count = diagnosis_.record_connect_failure()) {
        if (count == 1) {
            spdlog::warn("{} cannot connect to {}: {}", options_.log_name, brokers_.url(), reason);
        } else {
            spdlog::warn("{} cannot connect to {}: {} ({} failed attempts)", options_.log_name,
                         brokers_.url(), reason, count);
        }
        brokers_.move_to_next();
        spdlog::info("{} reconnecting to {} in {} ms", options_.log_name, brokers_.url(),
                     schedule_reconnect().count());
    } else {
        brokers_.move_to_next();
        schedule_reconnect();
    }
}

void Connection::on_connection_lost(std::string cause, bool silent) {
    // A connection ended on purpose and lost before Paho finished its DISCONNECT (the broker
    // went meanwhile): Paho may never answer that DISCONNECT, and the session is over anyway.
    if (state_ == State::ending) {
        on_session_ended();
        return;
    }
    if (state_ != State::connected) {
        return;
    }
    cause = diagnosis_.explain_loss(std::move(cause), silent);
    counters_.connected = false;
    ConnectionCounters::bump(counters_.connection_losses);
    spdlog::warn("{} connection to {} lost: {}", options_.log_name, brokers_.url(), cause);
    nagle_.detach();
    sender_.on_connection_lost();
    brokers_.move_to_next();
    spdlog::info("{} reconnecting to {} in {} ms", options_.log_name, brokers_.url(),
                 schedule_reconnect().count());
}

std::chrono::milliseconds Connection::schedule_reconnect() {
    state_ = State::waiting;
    return reconnect_.schedule([this] {
        if (state_ == State::waiting) {
            do_connect();
        }
    });
}

// --- a session ended on purpose ------------------------------------------------------------

void Connection::DisconnectListener::on_success(const paho::token&) {
    connection_.loop_.post([&c = connection_] { c.on_session_ended(); });
}

void Connection::DisconnectListener::on_failure(const paho::token&) {
    connection_.loop_.post([&c = connection_] { c.on_session_ended(); });
}

void Connection::end_session() {
    start_pending_ = false;
    if (state_ == State::idle || state_ == State::ending || state_ == State::stopped) return;
    const auto was = state_;
    state_ = State::idle;
    reconnect_.cancel();
    reconnect_.reset();
    if (was == State::connected) {
        counters_.connected = false;
        nagle_.detach();
        sender_.set_link_up(false);
        // Session-bound: what waits belonged to this connection and goes with it. A burst the
        // thread took before is handed over whole first, so the will is the last thing said.
        sender_.on_connection_lost();
        sender_.wait_idle();
        publish_last_will();
    } else {
        // An attempt that may connect yet: it is disconnected, its will never said.
        last_will_.forget();
    }
    if (was == State::connected || was == State::connecting) {
        try {
            // Paho sends the will before the DISCONNECT (waiting up to the timeout for its
            // PUBACK), and cancels an attempt in progress. Nothing here waits for it.
            const auto token = paho_.disconnect(disconnect_options(std::chrono::seconds(1)));
            state_ = State::ending;
            // Paho takes no listener with options: one set after a disconnect that completed
            // meanwhile is never called, so that case is answered here (on_session_ended()
            // runs once: the second finds the state moved on).
            token->set_action_callback(disconnect_listener_);
            if (token->is_complete()) loop_.post([this] { on_session_ended(); });
        } catch (const paho::exception& e) {
            spdlog::warn("{} disconnect failed: {}", options_.log_name, e.what());
        }
    }
    spdlog::info("{} session ended with {}", options_.log_name, brokers_.url());
}

void Connection::leave_broker() {
    end_session();
    brokers_.move_to_next();
    start();
}

paho::disconnect_options Connection::disconnect_options(std::chrono::seconds timeout) const {
    paho::disconnect_options options(timeout);
    if (options_.disconnect_with_will && options_.version == 5) {
        options.set_reason_code(paho::ReasonCode::DISCONNECT_WITH_WILL_MESSAGE);
        paho::disconnect_options_test::send_reason_code(options);
    }
    return options;
}

void Connection::on_session_ended() {
    if (state_ != State::ending) return;
    state_ = State::idle;
    if (std::exchange(start_pending_, false)) do_connect();
}

// --- stop()'s steps and the counters -------------------------------------------------------

void Connection::add_stats(ClientStats& stats) const {
    counters_.add_to(stats);
    if (stats.connected) stats.broker = brokers_.url();
}

void Connection::on_stopped() {
    state_ = State::stopped;
    counters_.connected = false;
    reconnect_.cancel();
}

bool Connection::link_alive() const { return sender_.link_up() && paho_.is_connected(); }

paho::delivery_token_ptr Connection::publish_last_will() {
    std::optional<Message> will = last_will_.take();
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

paho::delivery_token_ptr Connection::publish_offline(core::MonoTime deadline) {
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
        return sender_.publish_own(availability_message(options_, "offline"), generation);
    } catch (const paho::exception& e) {
        spdlog::warn("{} cannot publish availability: {}", options_.log_name, e.what());
    }
    return nullptr;
}

void Connection::disconnect() {
    try {
        paho_.disconnect(disconnect_options(std::chrono::seconds(1)))
            ->wait_for(std::chrono::seconds(2));
    } catch (const paho::exception& e) {
        spdlog::warn("{} disconnect failed: {}", options_.log_name, e.what());
    }
    sender_.set_link_up(false);
    counters_.connected = false;
    spdlog::info("{} disconnected from {}", options_.log_name, brokers_.url());
}

}  // namespace eip2mqtt::adapters::mqtt::detail
