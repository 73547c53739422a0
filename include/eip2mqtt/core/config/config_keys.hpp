#pragma once
/// Every key of the configuration file, mapping by mapping: the keys the YAML loader accepts (its
/// unknown-key errors and "did you mean" read these lists), what a reload does when one changes,
/// and how to tell in the model that it changed. One entry per key, in one place: a key cannot
/// be read without a reload rule, and plan_reload (reload_plan.hpp) compares exactly these.

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string_view>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/enum_names.hpp"

namespace eip2mqtt::core::config {

/// What a reload does with a key whose value changed.
enum class ReloadRule : std::uint8_t {
    /// The running gateway applies it. An exchange's or a tag's key restarts that exchange
    /// alone; a section's key is applied without restarting any exchange.
    live,
    /// Only a restart applies it (the MQTT session, a socket, the gateway's identity): a reload
    /// that changes it is refused whole, and nothing of it is applied.
    restart,
};

inline constexpr auto reload_rule_names = enum_names<ReloadRule>("live", "restart");

constexpr std::string_view to_string(ReloadRule rule) { return reload_rule_names.name_of(rule); }

/// One key of a mapping whose values `Of` holds.
template <class Of>
struct ConfigKey {
    std::string_view name;  ///< as written in YAML
    ReloadRule rule;
    /// Whether `a` and `b` differ in this key. Null for a key whose value is a mapping that its
    /// own keys compare (`buffer`, `store_and_forward`, `tags`), and for a list entry's keys,
    /// which their list compares (`eip.multicast`).
    bool (*differs)(const Of& a, const Of& b);
};

namespace keys {

/// Whether `a` and `b` differ in what `field` (a data member or an accessor) reads.
template <auto field, class Of>
constexpr bool differs(const Of& a, const Of& b) {
    return !(std::invoke(field, a) == std::invoke(field, b));
}

inline constexpr auto live = ReloadRule::live;
inline constexpr auto restart = ReloadRule::restart;

inline constexpr std::array<ConfigKey<GatewaySection>, 6> gateway{{
    {"id", restart, differs<&GatewaySection::id>},
    {"state_dir", restart, differs<&GatewaySection::state_dir>},
    {"log_level", live, differs<&GatewaySection::log_level>},
    // The defaults of consumed exchanges: those that take them restart (plan_diff).
    {"timestamp", live,
     [](const GatewaySection& a, const GatewaySection& b) {
         return a.exchange_defaults.timestamp != b.exchange_defaults.timestamp;
     }},
    {"clock_tolerance_ms", live,
     [](const GatewaySection& a, const GatewaySection& b) {
         return a.exchange_defaults.clock_tolerance != b.exchange_defaults.clock_tolerance;
     }},
    // Every tag's topic may move, as with base_topic.
    {"location", restart, differs<&GatewaySection::location>},
}};

/// The connection's settings need a restart (a new session); how tags are published is applied
/// live, the retained state republished in the new form.
inline constexpr std::array<ConfigKey<MqttSection>, 25> mqtt{{
    {"name", restart, differs<&MqttSection::name>},
    {"writes", restart, differs<&MqttSection::writes>},
    {"url", restart, differs<&MqttSection::urls>},
    {"version", restart, differs<&MqttSection::version>},
    {"client_id", restart, differs<&MqttSection::client_id>},
    {"username", restart, differs<&MqttSection::username>},
    {"password_file", restart, differs<&MqttSection::password_file>},
    {"tls", restart,
     [](const MqttSection& a, const MqttSection& b) {
         return a.tls.has_value() != b.tls.has_value();
     }},
    {"base_topic", restart, differs<&MqttSection::base_topic>},
    {"topic_template", restart, differs<&MqttSection::topic_template>},
    {"qos", live, differs<&MqttSection::qos>},
    {"retain", live, differs<&MqttSection::retain>},
    {"payload", live, differs<&MqttSection::payload>},
    {"buffer", live, nullptr},
    {"batch", live, differs<&MqttSection::batch>},
    {"batch_first", live, differs<&MqttSection::batch_first>},
    {"keepalive_s", restart, differs<&MqttSection::keepalive>},
    {"metrics_interval_s", live, differs<&MqttSection::metrics_interval>},
    {"session_expiry_s", restart, differs<&MqttSection::session_expiry>},
    {"allow_response_topics_under_base", live,
     differs<&MqttSection::allow_response_topics_under_base>},
    {"store_and_forward", restart, nullptr},
    // The connection's: how it describes what it sends.
    {"describe_payloads", restart, differs<&MqttSection::describe_payloads>},
    {"properties", restart, differs<&MqttSection::properties>},
    {"message_expiry_s", restart, differs<&MqttSection::message_expiry>},
    {"topic_aliases", restart, differs<&MqttSection::topic_aliases>},
}};

/// `mqtt.tls`, compared when both configurations have one (`tls` itself says when one lacks it).
inline constexpr std::array<ConfigKey<TlsSection>, 4> tls{{
    {"ca_file", restart, differs<&TlsSection::ca_file>},
    {"cert_file", restart, differs<&TlsSection::cert_file>},
    {"key_file", restart, differs<&TlsSection::key_file>},
    {"verify", restart, differs<&TlsSection::verify>},
}};

inline constexpr std::array<ConfigKey<MqttSection>, 1> buffer{{
    {"max_messages", live, differs<&MqttSection::buffer_max_messages>},
}};

/// The journal is opened at start, with the MQTT connection it replays on.
inline constexpr std::array<ConfigKey<StoreAndForwardSection>, 4> store_and_forward{{
    {"enabled", restart, differs<&StoreAndForwardSection::enabled>},
    {"max_mb", restart, differs<&StoreAndForwardSection::max_mb>},
    {"replay_rate", restart, differs<&StoreAndForwardSection::replay_rate>},
    {"fsync_interval_ms", restart, differs<&StoreAndForwardSection::fsync_interval>},
}};

/// The receiving socket stays bound; its multicast groups are left and joined live. The sending
/// socket keeps the TTL and interface it was opened with.
/// `link_mbps` only bounds what `check` accepts: nothing runs on it.
inline constexpr std::array<ConfigKey<EipSection>, 7> eip{{
    {"bind", restart, differs<&EipSection::bind>},
    {"port", restart, differs<&EipSection::port>},
    {"multicast", live, differs<&EipSection::multicast>},
    {"multicast_ttl", restart, differs<&EipSection::multicast_ttl>},
    {"multicast_interface", restart, differs<&EipSection::multicast_interface>},
    {"link_mbps", live, differs<&EipSection::link_mbps>},
    {"commands", live, nullptr},
}};

/// `eip.commands`: the responder's socket is opened at start; who it answers, how often, and
/// whether it writes are applied live.
inline constexpr std::array<ConfigKey<CommandsSection>, 7> commands{{
    {"enabled", restart, differs<&CommandsSection::enabled>},
    {"port", restart, differs<&CommandsSection::port>},
    {"allow", live, differs<&CommandsSection::allow>},
    {"trusted", live, differs<&CommandsSection::trusted>},
    {"writes", live, differs<&CommandsSection::writes>},
    {"max_requests_per_s", live, differs<&CommandsSection::max_requests_per_s>},
    {"max_requests_per_s_per_source", live,
     differs<&CommandsSection::max_requests_per_s_per_source>},
}};

/// An entry of `eip.multicast`: a change to it is a change to the list.
inline constexpr std::array<ConfigKey<MulticastGroup>, 2> multicast{{
    {"group", live, nullptr},
    {"interface", live, nullptr},
}};

/// The listener is made at start, with who may read it and how.
inline constexpr std::array<ConfigKey<MetricsSection>, 3> metrics{{
    {"listen", restart, differs<&MetricsSection::listen>},
    {"auth", restart, differs<&MetricsSection::auth>},
    {"tls", restart, differs<&MetricsSection::tls>},
}};

inline constexpr std::array<ConfigKey<MetricsAuth>, 2> metrics_auth{{
    {"username", restart, nullptr},
    {"password_file", restart, nullptr},
}};

inline constexpr std::array<ConfigKey<MetricsTls>, 2> metrics_tls{{
    {"cert", restart, nullptr},
    {"key", restart, nullptr},
}};

/// The edge node's identity and births are made at start.
inline constexpr std::array<ConfigKey<SparkplugSection>, 7> sparkplug{{
    {"group_id", restart, differs<&SparkplugSection::group_id>},
    {"edge_node_id", restart, differs<&SparkplugSection::edge_node_id>},
    {"primary_host_id", restart, differs<&SparkplugSection::primary_host_id>},
    {"uns", restart, differs<&SparkplugSection::uns>},
    {"connection", restart, differs<&SparkplugSection::connection>},
    {"qos", restart, differs<&SparkplugSection::qos>},
    // The node takes its packet limit when it connects, with the broker's.
    {"max_packet_bytes", restart, differs<&SparkplugSection::max_packet_bytes>},
}};

/// The pair's lease is taken at start, on a connection of its own.
inline constexpr std::array<ConfigKey<RedundancySection>, 3> redundancy{{
    {"pair", restart, differs<&RedundancySection::pair>},
    {"takeover_ms", restart, differs<&RedundancySection::takeover>},
    {"priority", restart, differs<&RedundancySection::priority>},
}};

/// An exchange's keys restart that exchange (its name is what matches it: a new name is another
/// exchange, started, and the old one stopped).
inline constexpr std::array<ConfigKey<plan::ExchangeSpec>, 17> exchange{{
    {"name", live, differs<&plan::ExchangeSpec::name>},
    {"direction", live, differs<&plan::ExchangeSpec::direction>},
    {"producer_id", live, differs<&plan::ExchangeSpec::producer_id>},
    {"exchange_id", live, differs<&plan::ExchangeSpec::exchange_id>},
    {"length", live, differs<&plan::ExchangeSpec::length>},
    {"signature", live, differs<&plan::ExchangeSpec::signature>},
    {"period_ms", live, differs<&plan::ExchangeSpec::period>},
    {"timeout_ms", live, differs<&plan::ExchangeSpec::timeout>},
    {"timestamp", live, differs<&plan::ExchangeSpec::timestamp>},
    {"clock_tolerance_ms", live, differs<&plan::ExchangeSpec::clock_tolerance>},
    {"source", live, differs<&plan::ExchangeSpec::source>},
    {"destination", live, differs<&plan::ExchangeSpec::destination>},
    {"topic", live, differs<&plan::ExchangeSpec::topic>},
    {"points", live, differs<&plan::ExchangeSpec::points>},
    {"publish_raw", live, differs<&plan::ExchangeSpec::publish_raw>},
    {"location", live, differs<&plan::ExchangeSpec::location>},
    {"tags", live, nullptr},
}};

/// A tag's keys restart its exchange (a tag is matched by name, as exchanges are). The rows of
/// a point list are tags too: a changed row shows as the keys it changed.
inline constexpr std::array<ConfigKey<plan::TagSpec>, 21> tag{{
    {"name", live, differs<&plan::TagSpec::name>},
    {"address", live, differs<&plan::TagSpec::address>},
    {"type", live, differs<&plan::TagSpec::type>},
    {"unit", live, differs<&plan::TagSpec::unit>},
    {"deadband", live,
     [](const plan::TagSpec& a, const plan::TagSpec& b) {
         return a.deadband != b.deadband || a.deadband_percent() != b.deadband_percent();
     }},
    {"refresh_s", live, differs<&plan::TagSpec::refresh>},
    {"writable", live, differs<&plan::TagSpec::writable>},
    {"min", live, differs<&plan::TagSpec::min>},
    {"max", live, differs<&plan::TagSpec::max>},
    {"initial", live, differs<&plan::TagSpec::initial>},
    {"description", live, differs<&plan::TagSpec::description>},
    {"max_writes_per_s", live, differs<&plan::TagSpec::max_writes_per_s>},
    // `type_eu` is kept in the scale, but named as its own key.
    {"scale", live,
     [](const plan::TagSpec& a, const plan::TagSpec& b) {
         const auto without_type = [](const plan::TagSpec& t) {
             auto scale = t.scale();
             if (scale) scale->eu_type.reset();
             return scale;
         };
         return without_type(a) != without_type(b);
     }},
    {"type_eu", live,
     [](const plan::TagSpec& a, const plan::TagSpec& b) {
         const auto eu_type = [](const plan::TagSpec& t) {
             return t.scale() ? t.scale()->eu_type : std::nullopt;
         };
         return eu_type(a) != eu_type(b);
     }},
    {"publish_raw", live, differs<&plan::TagSpec::publish_raw>},
    // A string's length is its count of bytes.
    {"count", live,
     [](const plan::TagSpec& a, const plan::TagSpec& b) {
         return a.count != b.count && a.type != plan::TagType::string;
     }},
    {"length", live,
     [](const plan::TagSpec& a, const plan::TagSpec& b) {
         return a.count != b.count && a.type == plan::TagType::string;
     }},
    {"trim", live, differs<&plan::TagSpec::trim>},
    {"location", live, differs<&plan::TagSpec::location>},
    {"topic_name", live, differs<&plan::TagSpec::topic_name>},
    {"topic", live, differs<&plan::TagSpec::topic>},
}};

/// A tag's `scale`, compared whole by the tag's `scale` key.
inline constexpr std::array<ConfigKey<plan::Scaling>, 6> scale{{
    {"raw", live, differs<&plan::Scaling::raw>},
    {"eu", live, differs<&plan::Scaling::eu>},
    {"sqrt", live, differs<&plan::Scaling::kind>},
    {"clamp", live, differs<&plan::Scaling::clamp>},
    {"gain", live, differs<&plan::Scaling::gain>},
    {"offset", live, differs<&plan::Scaling::offset>},
}};

/// A tag's `deadband` written as a mapping.
inline constexpr std::array<ConfigKey<plan::TagExtras>, 1> deadband{{
    {"percent", live, differs<&plan::TagExtras::deadband_percent>},
}};

/// The names of `table`'s keys, in its order (the loader's lists of known keys).
template <class Of, std::size_t N>
constexpr std::array<std::string_view, N> names(const std::array<ConfigKey<Of>, N>& table) {
    std::array<std::string_view, N> out{};
    for (std::size_t i = 0; i < N; ++i) out[i] = table[i].name;
    return out;
}

}  // namespace keys
}  // namespace eip2mqtt::core::config
