// The Connection's way down: failed attempts, lost connections, the reconnect backoff, and a
// session ended on purpose.

#include <spdlog/spdlog.h>

#include <utility>

#include "adapters/mqtt/detail/connection.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

void Connection::on_connect_failed(std::string reason, int return_code) {
    reason = explain_connect_failure(std::move(reason));
    if (options_.version == 5) {
        if (auto refusal = mqtt5_refusal(return_code, reason, endpoint() && endpoint()->tls)) {
            // Paho has no words for the 3.1.1 return code 1 ("Unknown error code 1").
            reason = return_code == 1 ? std::move(*refusal) : reason + ": " + *refusal;
        }
    }
    if (const auto count = connect_failure_log_.record(Clock::now())) {
        if (count == 1) {
            spdlog::warn("{} cannot connect to {}: {}", options_.log_name, url(), reason);
        } else {
            spdlog::warn("{} cannot connect to {}: {} ({} failed attempts)", options_.log_name,
                         url(), reason, count);
        }
        move_to_next_broker();
        spdlog::info("{} reconnecting to {} in {} ms", options_.log_name, url(),
                     schedule_reconnect().count());
    } else {
        move_to_next_broker();
        schedule_reconnect();
    }
}

std::string Connection::explain_connect_failure(std::string reason) const {
    if (reason != paho::exception::error_str(MQTTASYNC_FAILURE)) {
        return reason;  // the broker gave a reason code, or Paho a specific error
    }
    try {
        // Completed (or about to be, see apply_broker_limits): throws its error, which
        // carries Paho's message.
        if (connect_token_) {
            connect_token_->wait_for(std::chrono::seconds(1));
        }
    } catch (const paho::exception& e) {
        if (!e.get_message().empty() && e.get_message() != reason) {
            reason += ": " + e.get_message();
        }
    }
    if (endpoint() && endpoint()->tls) {
        // Paho C++ 1.2 cannot safely report OpenSSL's reason.
        reason +=
            " (TLS handshake failed or the broker closed the connection: check that "
            "mqtt.tls.ca_file signed the broker's certificate, that the certificate names " +
            endpoint()->host + ", and whether the broker requires a client certificate)";
    }
    return reason;
}

void Connection::on_connection_lost(std::string cause, bool silent) {
    if (state_ != State::connected) {
        return;
    }
    if (silent_losses_.on_loss(silent, Clock::now() - connected_at_)) {
        cause = "no reason given: " + SilentLossPattern::explain(options_.client_id);
    } else if (silent) {
        cause = "no reason given (no DISCONNECT from the broker)";
    }
    connected_ = false;
    connection_losses_.fetch_add(1, std::memory_order_relaxed);
    spdlog::warn("{} connection to {} lost: {}", options_.log_name, url(), cause);
    nagle_.detach();
    sender_.on_connection_lost();
    move_to_next_broker();
    spdlog::info("{} reconnecting to {} in {} ms", options_.log_name, url(),
                 schedule_reconnect().count());
}

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
    reconnect_timer_.cancel();
    backoff_.reset();
    if (was == State::connected) {
        connected_ = false;
        nagle_.detach();
        sender_.set_link_up(false);
        // Session-bound: what waits belonged to this connection and goes with it. A burst the
        // thread took before is handed over whole first, so the will is the last thing said.
        sender_.on_connection_lost();
        sender_.wait_idle();
        publish_last_will();
    } else {
        // An attempt that may connect yet: it is disconnected, its will never said.
        std::lock_guard lock(will_mutex_);
        last_will_.reset();
    }
    if (was == State::connected || was == State::connecting) {
        try {
            // Paho sends the will before the DISCONNECT (waiting up to the timeout for its
            // PUBACK), and cancels an attempt in progress. Nothing here waits for it.
            paho_.disconnect(std::chrono::seconds(1), nullptr, disconnect_listener_);
            state_ = State::ending;
        } catch (const paho::exception& e) {
            spdlog::warn("{} disconnect failed: {}", options_.log_name, e.what());
        }
    }
    spdlog::info("{} session ended with {}", options_.log_name, url());
}

void Connection::on_session_ended() {
    if (state_ != State::ending) return;
    state_ = State::idle;
    if (std::exchange(start_pending_, false)) do_connect();
}

void Connection::move_to_next_broker() { broker_ = next_broker(broker_, options_.urls.size()); }

std::chrono::milliseconds Connection::schedule_reconnect() {
    state_ = State::waiting;
    // Doubling, but never more than a quarter of the outage's age: a short outage is noticed
    // soon after the broker is back (detail/reconnect_backoff.hpp).
    const auto delay = backoff_.next(Clock::now());
    reconnect_timer_.expires_after(delay);
    reconnect_timer_.async_wait(loop_.guarded([this](boost::system::error_code ec) {
        if (ec == boost::asio::error::operation_aborted) {
            return;
        }
        if (state_ == State::waiting) {
            do_connect();
        }
    }));
    return delay;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
