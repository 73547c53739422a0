#pragma once
/// The semantic checks of a configuration (config.hpp's validate): one Validator walks the
/// model and collects every problem. Its checks are in two files: validator.cpp (the run and
/// the gateway and mqtt sections) and exchange_checks.cpp (each exchange's keys and topic); those
/// of each tag (its name, address and values) are TagChecks' (tag_checks.hpp).
///
/// Module-private to src/core/config.

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/config/detail/tag_checks.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::core::config::detail {

inline constexpr long long min_period_ms = 2;        // docs/protocol.md §5
inline constexpr long long max_period_ms = 3600000;  // docs/protocol.md §5
/// MQTT encodes the length of a string (a client id) in two bytes, as a topic's.
inline constexpr std::size_t max_string_bytes = plan::max_topic_bytes;

// The fixed parts of the longest topics the gateway builds: {base}/{topic}/set/result for an
// exchange (longer than its /_status and /_values), {base}/{topic}/{tag}/set/result for a tag,
// {base}/_gateway/{id}/metrics for the gateway (longer than /state). Their lengths are added
// up, the topics never built: a configuration may hold 100,000 tags.
inline constexpr std::string_view result_suffix = "/set/result";
inline constexpr std::string_view gateway_level = "/_gateway/";
inline constexpr std::string_view metrics_suffix = "/metrics";

/// "makes topic '{pattern}' N bytes long (MQTT allows 65535)".
std::string too_long(std::string_view pattern, std::size_t bytes);

class Validator {
public:
    explicit Validator(const Config& config) : config_(config) {}

    /// Every problem of the configuration, in file order.
    Diagnostics run();

private:
    void error(const Mark& mark, std::string message) {
        out_.push_back({mark, std::move(message)});
    }

    void check_gateway();
    /// Every connection of `mqtt`, then the list as a whole (connection_list_check.hpp).
    void check_mqtt();
    /// One connection's keys; returns whether its base_topic is a valid topic.
    bool check_connection(const MqttSection& mqtt);
    void check_client_id(const MqttSection& mqtt);
    void check_connection_keys(const MqttSection& mqtt);
    /// The gateway's own topics fit MQTT's length. A base_topic too long for any of them is
    /// said once, here, and the lengths of exchange and tag topics are not checked then.
    void check_gateway_topics();

    void check_exchanges();
    void check_exchange(const ExchangeConfig& exchange);
    /// The keys that only one direction may have.
    void check_direction(const ExchangeConfig& exchange, const std::string& what);
    /// The exchange's topic; returns the length of {base}/{topic}, or 0 when it is unknown or
    /// already too long (its tags' topics are then not checked for length).
    std::size_t check_exchange_topic(const ExchangeConfig& exchange, const std::string& what);

    const Config& config_;
    Diagnostics out_;
    bool id_ok_ = false;    ///< gateway.id is a valid topic level
    bool base_ok_ = false;  ///< base_topic is a valid topic, short enough for some under it
    TagChecks tags_;
};

}  // namespace eip2mqtt::core::config::detail
