#include "adapters/mqtt/detail/connection_reasons.hpp"

#include <fmt/format.h>

namespace eip2mqtt::adapters::mqtt::detail {
namespace {

constexpr std::string_view kVersionFix = "set mqtt.version: 3.1.1";

}  // namespace

std::string describe_disconnect(int reason_code, std::string_view reason_text,
                                std::string_view client_id) {
    if (reason_code == kSessionTakenOver) {
        return fmt::format(
            "another client connected with the same client id '{}' (MQTT 5 reason 0x8E, session "
            "taken over); two gateways with one client id take turns: give each its own "
            "mqtt.client_id",
            client_id);
    }
    return fmt::format("broker sent DISCONNECT: {} (MQTT 5 reason 0x{:02X})", reason_text,
                       reason_code);
}

std::optional<std::string> mqtt5_refusal(int return_code, std::string_view failure, bool tls) {
    // Paho C 1.3's words when the socket closes while it waits for the CONNACK.
    if (failure.find("TCP connect completion failure") != std::string_view::npos) {
        if (tls) {
            // A broker that wants a client certificate closes the same way after a TLS 1.3
            // handshake: the TLS checks come first.
            return fmt::format(
                "if the TLS settings are right, the broker may have refused MQTT 5, as brokers "
                "that speak only MQTT 3.1.1 do (RabbitMQ before 3.13, for one): then {}",
                kVersionFix);
        }
        return fmt::format(
            "the broker refused MQTT 5: it closed the connection on our MQTT 5 CONNECT without a "
            "CONNACK, as brokers that speak only MQTT 3.1.1 do (RabbitMQ before 3.13, for one), "
            "and as a proxy or load balancer does whose broker is down; if it is a 3.1.1 broker, "
            "{}",
            kVersionFix);
    }
    if (return_code == 1) {
        // Return code 1 of a 3.1.1 CONNACK; not a reason code of MQTT 5.
        return fmt::format(
            "the broker refused MQTT 5 (it answered in MQTT 3.1.1: unacceptable protocol "
            "version); {}",
            kVersionFix);
    }
    if (return_code == kUnsupportedProtocolVersion) {
        return fmt::format("the broker refused MQTT 5 (reason 0x84); {}", kVersionFix);
    }
    return std::nullopt;
}

bool SilentLossPattern::on_loss(bool silent, std::chrono::steady_clock::duration lived) {
    in_a_row_ = silent && lived < kShortLived ? in_a_row_ + 1 : 0;
    return in_a_row_ >= kLossesInARow;
}

std::string SilentLossPattern::explain(std::string_view client_id) {
    return fmt::format(
        "{} connections in a row were closed without a reason within {} s of connecting: another "
        "client is probably connecting with the same client id '{}' (a broker that does not send "
        "MQTT 5 reason 0x8E, such as Mosquitto before 2.0.15, closes the older connection "
        "silently); two gateways with one client id take turns: give each its own "
        "mqtt.client_id",
        kLossesInARow, kShortLived.count(), client_id);
}

}  // namespace eip2mqtt::adapters::mqtt::detail
