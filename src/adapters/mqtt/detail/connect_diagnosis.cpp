#include "adapters/mqtt/detail/connect_diagnosis.hpp"

#include <chrono>
#include <utility>

namespace eip2mqtt::adapters::mqtt::detail {

namespace paho = ::mqtt;

namespace {

/// Adds what `token` knows and, over TLS, what to check, to Paho's generic failure.
std::string explain_generic_failure(std::string reason, const paho::token_ptr& token,
                                    const std::optional<BrokerEndpoint>& endpoint) {
    if (reason != paho::exception::error_str(MQTTASYNC_FAILURE)) {
        return reason;  // the broker gave a reason code, or Paho a specific error
    }
    try {
        // Completed (or about to be, see Connection::apply_broker_limits): throws its error,
        // which carries Paho's message.
        if (token) {
            token->wait_for(std::chrono::seconds(1));
        }
    } catch (const paho::exception& e) {
        if (!e.get_message().empty() && e.get_message() != reason) {
            reason += ": " + e.get_message();
        }
    }
    if (endpoint && endpoint->tls) {
        // Paho C++ 1.2 cannot safely report OpenSSL's reason.
        reason +=
            " (TLS handshake failed or the broker closed the connection: check that "
            "mqtt.tls.ca_file signed the broker's certificate, that the certificate names " +
            endpoint->host + ", and whether the broker requires a client certificate)";
    }
    return reason;
}

}  // namespace

void ConnectDiagnosis::on_connected() {
    connected_at_ = options_.clock->monotonic();
    connect_failure_log_.reset();
}

std::string ConnectDiagnosis::explain_connect_failure(
    std::string reason, int return_code, const paho::token_ptr& token,
    const std::optional<BrokerEndpoint>& endpoint) const {
    reason = explain_generic_failure(std::move(reason), token, endpoint);
    if (options_.version == 5) {
        if (auto refusal = mqtt5_refusal(return_code, reason, endpoint && endpoint->tls)) {
            // Paho has no words for the 3.1.1 return code 1 ("Unknown error code 1").
            reason = return_code == 1 ? std::move(*refusal) : reason + ": " + *refusal;
        }
    }
    return reason;
}

std::uint64_t ConnectDiagnosis::record_connect_failure() {
    return connect_failure_log_.record(options_.clock->monotonic());
}

std::string ConnectDiagnosis::explain_loss(std::string cause, bool silent) {
    if (silent_losses_.on_loss(silent, options_.clock->monotonic() - connected_at_)) {
        return "no reason given: " + SilentLossPattern::explain(options_.client_id);
    }
    if (silent) {
        return "no reason given (no DISCONNECT from the broker)";
    }
    return cause;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
