// The gateway, mqtt, metrics and sparkplug sections of the configuration.

#include <algorithm>

#include "adapters/yaml/detail/key_readers.hpp"
#include "adapters/yaml/detail/sections.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

namespace keys = core::config::keys;

/// How each key of `gateway` is read.
constexpr KeyReader<GatewaySection> gateway_rows[]{
    {"id", [](KeyValue& v, GatewaySection& g) { return v.text_to(g.id); }},
    {"state_dir", [](KeyValue& v, GatewaySection& g) { return v.text_to(g.state_dir); }},
    {"log_level",
     [](KeyValue& v, GatewaySection& g) {
         const auto s = v.text();
         if (s) g.log_level = lower(*s);
         return s.has_value();
     }},
    {"timestamp",
     [](KeyValue& v, GatewaySection& g) {
         const auto source = v.timestamp_source();
         if (source) g.exchange_defaults.timestamp = *source;
         return source.has_value();
     }},
    {"clock_tolerance_ms",
     [](KeyValue& v, GatewaySection& g) {
         return v.integer_to<long long>(g.exchange_defaults.clock_tolerance, 0);
     }},
    {"location", [](KeyValue& v, GatewaySection& g) { return v.location_to(g.location); }},
};
constexpr auto gateway_readers = bind_keys(keys::gateway, gateway_rows);

/// `mqtt.tls`
constexpr KeyReader<TlsSection> tls_rows[]{
    {"ca_file", [](KeyValue& v, TlsSection& t) { return v.text_to(t.ca_file); }},
    {"cert_file", [](KeyValue& v, TlsSection& t) { return v.text_to(t.cert_file); }},
    {"key_file", [](KeyValue& v, TlsSection& t) { return v.text_to(t.key_file); }},
    {"verify", [](KeyValue& v, TlsSection& t) { return v.boolean_to(t.verify); }},
};
constexpr auto tls_readers = bind_keys(keys::tls, tls_rows);

/// `mqtt.buffer`
constexpr KeyReader<MqttSection> buffer_rows[]{
    {"max_messages",
     [](KeyValue& v, MqttSection& m) {
         return v.integer_to<std::size_t>(m.buffer_max_messages, 1);
     }},
};
constexpr auto buffer_readers = bind_keys(keys::buffer, buffer_rows);

/// `mqtt.store_and_forward`
constexpr KeyReader<StoreAndForwardSection> store_and_forward_rows[]{
    {"enabled", [](KeyValue& v, StoreAndForwardSection& s) { return v.boolean_to(s.enabled); }},
    // A journal smaller than a megabyte would drop history at once.
    {"max_mb",
     [](KeyValue& v, StoreAndForwardSection& s) {
         return v.integer_to<std::uint64_t>(s.max_mb, 1, 1ULL << 30);
     }},
    {"replay_rate",
     [](KeyValue& v, StoreAndForwardSection& s) {
         return v.integer_to<std::uint32_t>(s.replay_rate, 1, 1000000);
     }},
    {"fsync_interval_ms",
     [](KeyValue& v, StoreAndForwardSection& s) {
         return v.integer_to<std::uint32_t>(s.fsync_interval, 10, 3600000);
     }},
};
constexpr auto store_and_forward_readers =
    bind_keys(keys::store_and_forward, store_and_forward_rows);

bool read_version(KeyValue& v, MqttSection& m) {
    const std::string text(v.node().scalar());
    if (text == "3.1.1") {
        m.version = 3;
    } else if (const auto n = parse_integer<int>(text)) {
        m.version = *n;  // validate() accepts 5 and 3
    } else {
        v.error("mqtt version must be 5 or 3.1.1");
        return false;
    }
    return true;
}

bool read_tls(KeyValue& v, MqttSection& m) {
    TlsSection tls;
    v.mapping("in mqtt.tls", tls_readers, tls);
    if (!v.node().is_null()) m.tls = tls;
    return true;
}

/// `properties: [unit, quality]`: each name at its own line and column; a name said twice once.
bool read_properties(KeyValue& v, MqttSection& m) {
    std::vector<Mark> marks;
    const auto names = v.texts(marks);
    if (!names) return false;
    bool read = true;
    m.properties.clear();
    for (std::size_t i = 0; i < names->size(); ++i) {
        const auto property = core::config::message_property_names.parse((*names)[i]);
        if (!property) {
            v.error_at(marks[i], "unknown property " + in_quotes((*names)[i]) +
                                     "; expected unit, quality, source_time, exchange or producer");
            read = false;
        } else if (std::find(m.properties.begin(), m.properties.end(), *property) ==
                   m.properties.end()) {
            m.properties.push_back(*property);
        }
    }
    return read;
}

bool read_payload(KeyValue& v, MqttSection& m) {
    const auto format =
        v.parsed([](std::string_view s) { return core::config::payload_format_names.parse(s); },
                 "is not json, raw, value, umh or kepware");
    if (format) m.payload = *format;
    return format.has_value();
}

std::string_view url_scheme(std::string_view url) {
    const auto sep = url.find("://");
    return sep == std::string_view::npos ? std::string_view() : url.substr(0, sep);
}

/// `url: tcp://a:1883` or `url: [tcp://a:1883, tcp://b:1883]`: the brokers, tried in turn.
/// A single string is checked by validate(), as it always was; a list's entries here, each at
/// its own line and column.
bool read_urls(KeyValue& v, MqttSection& m) {
    std::vector<Mark> marks;
    auto urls = v.texts(marks);
    if (!urls) return false;
    if (urls->empty()) {
        v.error("mqtt url is an empty list: give at least one broker");
        return false;
    }
    bool ok = true;
    const auto scheme = url_scheme(urls->front());
    for (std::size_t i = 0; i < urls->size() && v.node().is_sequence(); ++i) {
        const auto& url = (*urls)[i];
        if (url.empty()) {
            v.error_at(marks[i], "mqtt url is empty");
            ok = false;
        } else if (url_scheme(url) != scheme) {
            // One mqtt.tls block, and one Paho client whose TLS is set by its first URL.
            v.error_at(marks[i], "mqtt url " + in_quotes(url) + " does not use the scheme of " +
                                     in_quotes(urls->front()) +
                                     ": every broker of the list takes the same one");
            ok = false;
        }
    }
    if (ok) m.urls = std::move(*urls);
    return ok;
}

/// `mqtt`
constexpr KeyReader<MqttSection> mqtt_rows[]{
    {"name", [](KeyValue& v, MqttSection& m) { return v.text_to(m.name); }},
    {"writes",
     [](KeyValue& v, MqttSection& m) {
         bool writes = false;
         if (!v.boolean_to(writes)) return false;
         m.writes = writes;
         return true;
     }},
    {"url", read_urls},
    {"version", read_version},
    {"client_id", [](KeyValue& v, MqttSection& m) { return v.text_to(m.client_id); }},
    {"username", [](KeyValue& v, MqttSection& m) { return v.text_to(m.username); }},
    {"password_file", [](KeyValue& v, MqttSection& m) { return v.text_to(m.password_file); }},
    {"tls", read_tls},
    {"base_topic", [](KeyValue& v, MqttSection& m) { return v.text_to(m.base_topic); }},
    {"topic_template", [](KeyValue& v, MqttSection& m) { return v.text_to(m.topic_template); }},
    {"qos", [](KeyValue& v, MqttSection& m) { return v.integer_to<int>(m.qos); }},
    {"retain", [](KeyValue& v, MqttSection& m) { return v.boolean_to(m.retain); }},
    {"payload", read_payload},
    {"buffer",
     [](KeyValue& v, MqttSection& m) {
         v.mapping("in mqtt.buffer", buffer_readers, m);
         return true;
     }},
    {"batch", [](KeyValue& v, MqttSection& m) { return v.boolean_to(m.batch); }},
    {"batch_first", [](KeyValue& v, MqttSection& m) { return v.boolean_to(m.batch_first); }},
    {"keepalive_s",
     [](KeyValue& v, MqttSection& m) { return v.integer_to<int>(m.keepalive, 1, 65535); }},
    {"metrics_interval_s",
     [](KeyValue& v, MqttSection& m) { return v.integer_to<int>(m.metrics_interval, 1, 86400); }},
    {"session_expiry_s",
     [](KeyValue& v, MqttSection& m) {
         return v.integer_to<long long>(m.session_expiry, 0, 4294967295LL);
     }},
    {"allow_response_topics_under_base",
     [](KeyValue& v, MqttSection& m) { return v.boolean_to(m.allow_response_topics_under_base); }},
    {"store_and_forward",
     [](KeyValue& v, MqttSection& m) {
         auto& section = m.store_and_forward;
         section.marks = v.mapping("in mqtt.store_and_forward", store_and_forward_readers, section);
         return true;
     }},
    {"describe_payloads",
     [](KeyValue& v, MqttSection& m) { return v.boolean_to(m.describe_payloads); }},
    {"properties", read_properties},
    {"message_expiry_s",
     [](KeyValue& v, MqttSection& m) { return v.integer_to<std::uint32_t>(m.message_expiry, 0); }},
    {"topic_aliases", [](KeyValue& v, MqttSection& m) { return v.boolean_to(m.topic_aliases); }},
};
constexpr auto mqtt_readers = bind_keys(keys::mqtt, mqtt_rows);

/// `metrics.auth`
constexpr KeyReader<MetricsAuth> metrics_auth_rows[]{
    {"username", [](KeyValue& v, MetricsAuth& a) { return v.text_to(a.username); }},
    {"password_file", [](KeyValue& v, MetricsAuth& a) { return v.text_to(a.password_file); }},
};
constexpr auto metrics_auth_readers = bind_keys(keys::metrics_auth, metrics_auth_rows);

/// `metrics.tls`
constexpr KeyReader<MetricsTls> metrics_tls_rows[]{
    {"cert", [](KeyValue& v, MetricsTls& t) { return v.text_to(t.cert); }},
    {"key", [](KeyValue& v, MetricsTls& t) { return v.text_to(t.key); }},
};
constexpr auto metrics_tls_readers = bind_keys(keys::metrics_tls, metrics_tls_rows);

/// A mapping of `what` whose keys must all be given (`fields`: each key's name and value):
/// read into `out`, or an error naming the missing ones.
template <class Section, class Readers>
bool read_whole(KeyValue& v, const char* what, const Readers& readers,
                std::initializer_list<std::pair<const char*, std::string Section::*>> fields,
                std::optional<Section>& out) {
    Section section;
    v.mapping(std::string("in ") + what, readers, section);
    if (v.node().is_null()) return true;
    std::string missing;
    for (const auto& [name, field] : fields) {
        if ((section.*field).empty()) missing += (missing.empty() ? "" : " and ") + in_quotes(name);
    }
    if (!missing.empty()) {
        v.error(std::string(what) + " needs " + missing);
        return false;
    }
    out = std::move(section);
    return true;
}

/// `metrics`
constexpr KeyReader<MetricsSection> metrics_rows[]{
    {"listen",
     [](KeyValue& v, MetricsSection& m) {
         const auto s = v.text();
         if (!s || s->empty()) return s.has_value();
         // civetweb reads a list (',') as one listener per entry: a second, unchecked port.
         if (!valid_host_port(*s, true) || !one_host_port(*s)) {
             v.error("listen " + in_quotes(*s) + " is not one host:port");
             return false;
         }
         m.listen = *s;
         return true;
     }},
    {"auth",
     [](KeyValue& v, MetricsSection& m) {
         return read_whole(
             v, "metrics.auth", metrics_auth_readers,
             {{"username", &MetricsAuth::username}, {"password_file", &MetricsAuth::password_file}},
             m.auth);
     }},
    {"tls",
     [](KeyValue& v, MetricsSection& m) {
         return read_whole(v, "metrics.tls", metrics_tls_readers,
                           {{"cert", &MetricsTls::cert}, {"key", &MetricsTls::key}}, m.tls);
     }},
};
constexpr auto metrics_readers = bind_keys(keys::metrics, metrics_rows);

/// `sparkplug`
constexpr KeyReader<SparkplugSection> sparkplug_rows[]{
    {"group_id", [](KeyValue& v, SparkplugSection& s) { return v.text_to(s.group_id); }},
    {"edge_node_id", [](KeyValue& v, SparkplugSection& s) { return v.text_to(s.edge_node_id); }},
    {"primary_host_id",
     [](KeyValue& v, SparkplugSection& s) { return v.text_to(s.primary_host_id); }},
    {"uns", [](KeyValue& v, SparkplugSection& s) { return v.boolean_to(s.uns); }},
    {"connection", [](KeyValue& v, SparkplugSection& s) { return v.text_to(s.connection); }},
    {"qos",
     [](KeyValue& v, SparkplugSection& s) {
         if (!v.integer_to<int>(s.qos)) return false;
         if (s.qos != 0) {
             v.error("sparkplug qos " + std::to_string(s.qos) +
                     ": Sparkplug B 3.0 publishes births and data at QoS 0 only (hosts judge an "
                     "edge node by it); remove the key");
         }
         return true;
     }},
    // MQTT's own limit is 268,435,460 bytes; 0: none of ours.
    {"max_packet_bytes",
     [](KeyValue& v, SparkplugSection& s) {
         return v.integer_to<std::size_t>(s.max_packet_bytes, 0, 268435460);
     }},
};
constexpr auto sparkplug_readers = bind_keys(keys::sparkplug, sparkplug_rows);

}  // namespace

void read_gateway(Reader& reader, const Node& node, const Mark& at, Config& config) {
    config.gateway.marks =
        reader.read_keys(node, at, "gateway", "in gateway", gateway_readers, config.gateway);
}

/// `mqtt:` one connection's mapping, or a list of them (the first the main one).
void read_mqtt(Reader& reader, const Node& node, const Mark& at, Config& config) {
    if (!node.is_sequence()) {
        config.mqtt.marks =
            reader.read_keys(node, at, "mqtt", "in mqtt", mqtt_readers, config.mqtt);
        return;
    }
    if (node.size() == 0) {
        reader.error(at, "mqtt is an empty list: give at least one connection");
        return;
    }
    for (std::size_t i = 0; i < node.size(); ++i) {
        auto& section = i == 0 ? config.mqtt : config.more_mqtt.emplace_back();
        const auto item = node.item(i);
        const std::string what = "mqtt connection " + std::to_string(i + 1);
        section.marks =
            reader.read_keys(item, reader.mark(item), what, "in " + what, mqtt_readers, section);
    }
}

void read_metrics(Reader& reader, const Node& node, const Mark& at, Config& config) {
    config.metrics.marks =
        reader.read_keys(node, at, "metrics", "in metrics", metrics_readers, config.metrics);
}

void read_sparkplug(Reader& reader, const Node& node, const Mark& at, Config& config) {
    auto& sparkplug = config.sparkplug;
    sparkplug.marks =
        reader.read_keys(node, at, "sparkplug", "in sparkplug", sparkplug_readers, sparkplug);
    if (!node.is_null() && node.is_defined() && sparkplug.group_id.empty() &&
        !sparkplug.marks.contains("group_id")) {
        reader.error(sparkplug.marks.node,
                     "sparkplug lacks 'group_id' (required to enable Sparkplug B)");
    }
}

}  // namespace eip2mqtt::adapters::yaml::detail
