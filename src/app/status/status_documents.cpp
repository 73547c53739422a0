#include "eip2mqtt/app/status/status_documents.hpp"

#include <fmt/format.h>

#include <chrono>
#include <iterator>

#include "eip2mqtt/app/northbound/json_tree/json_tree_payload.hpp"
#include "eip2mqtt/core/json_text.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/quality/quality.hpp"

namespace eip2mqtt::app::status {
namespace {

namespace json_tree = northbound::json_tree;
using core::append_json_string;

/// `,"name":"text"`
void append_field(std::string& out, std::string_view name, std::string_view text) {
    fmt::format_to(std::back_inserter(out), R"(,"{}":)", name);
    append_json_string(out, text);
}

/// What every exchange's line starts with: who it is, and how it is configured.
void append_identity(std::string& out, const core::plan::ExchangePlan& plan) {
    const auto& spec = plan.spec;
    out += R"({"name":)";
    append_json_string(out, spec.name);
    append_field(out, "direction", core::plan::to_string(spec.direction));
    append_field(out, "topic", plan.topic);
    append_field(out, "producer", core::wire::to_string(spec.producer_id));
    fmt::format_to(std::back_inserter(out), R"(,"exchange_id":{},"period_ms":{},"tag_count":{})",
                   spec.exchange_id, spec.period.count(), plan.tags.size());
}

void append_consumer(std::string& out, const ExchangeConsumer& consumer, core::MonoTime now,
                     core::WallTime wall) {
    append_identity(out, consumer.plan());
    const auto status = consumer.status();
    fmt::format_to(std::back_inserter(out), R"(,"timeout_ms":{},"datagrams_per_s":{:.3f})",
                   consumer.plan().timeout.count(), consumer.arrivals().rate(now));
    out += R"(,"last_seen_age_ms":)";
    out += status.last_seen_ms ? std::to_string(core::to_ms(wall) - *status.last_seen_ms)
                               : std::string("null");
    out += R"(,"status":)";
    out += json_tree::format_status_payload(status);
}

void append_producer(std::string& out, const ExchangeProducer& producer) {
    const auto& plan = producer.plan();
    append_identity(out, plan);
    append_field(out, "destination", plan.spec.destination);
    const double rate = producer.paused() ? 0.0 : 1000.0 / double(plan.spec.period.count());
    fmt::format_to(std::back_inserter(out), R"(,"datagrams_per_s":{:.3f},"status":)", rate);
    out += json_tree::format_produced_status_payload(producer.status());
}

/// `,"tags":[...]`: each tag of `plan` with its sample from `image` (none: null).
void append_tags(std::string& out, const core::plan::ExchangePlan& plan,
                 std::span<const std::byte> image, std::optional<core::quality::Quality> quality,
                 std::int64_t timestamp_ms, const Sparklines* sparklines, std::int64_t now_ms) {
    out += R"(,"tags":[)";
    std::string sample;
    for (std::size_t i = 0; i < plan.tags.size(); ++i) {
        const auto& spec = plan.tags[i].spec;
        out += i == 0 ? R"({"name":)" : R"(,{"name":)";
        append_json_string(out, spec.name);
        append_field(out, "type", core::plan::to_string(spec.type));
        if (!spec.unit().empty()) append_field(out, "unit", spec.unit());
        append_field(out, "topic", plan.tag_topic(plan.tags[i]));
        out += R"(,"sample":)";
        if (quality && !image.empty()) {
            json_tree::format_tag_payload(sample, plan.spec.name, spec,
                                          core::plan::decode_tag(image, spec), *quality,
                                          timestamp_ms, core::config::PayloadFormat::json);
            out += sample;
        } else {
            out += "null";
        }
        if (sparklines != nullptr) sparklines->append_json(out, plan, i, now_ms);
        out += '}';
    }
    out += ']';
}

/// `,"mqtt":{…}`: the main connection, and each broker of its list with whether it is the one
/// connected to.
void append_mqtt(std::string& out, std::span<const std::string> brokers,
                 const adapters::mqtt::ClientStats& mqtt) {
    fmt::format_to(std::back_inserter(out),
                   R"(,"mqtt":{{"connected":{},"connects":{},"connection_losses":{},"brokers":[)",
                   mqtt.connected, mqtt.connects, mqtt.connection_losses);
    for (std::size_t i = 0; i < brokers.size(); ++i) {
        out += i != 0 ? R"(,{"url":)" : R"({"url":)";
        append_json_string(out, brokers[i]);
        fmt::format_to(std::back_inserter(out), R"(,"connected":{}}})",
                       mqtt.connected && mqtt.broker == brokers[i]);
    }
    out += "]}";
}

void append_connection(std::string& out, const adapters::metrics::ConnectionMetrics& connection) {
    out += R"({"name":)";
    append_json_string(out, connection.name);
    fmt::format_to(std::back_inserter(out), R"(,"connected":{},"broker":)", connection.connected);
    append_json_string(out, connection.broker);
    fmt::format_to(std::back_inserter(out), R"(,"published":{},"buffered":{},"journaled":)",
                   connection.published, connection.buffered);
    out += connection.history ? std::to_string(connection.history->entries) : "null";
    out += '}';
}

/// `,"connections":[…]`: with several MQTT connections, each one's state; empty with one.
void append_connections(std::string& out, const MetricsSources& sources) {
    out += R"(,"connections":[)";
    bool first = true;
    for (const auto& connection : connections_metrics(sources)) {
        if (!std::exchange(first, false)) out += ',';
        append_connection(out, connection);
    }
    out += ']';
}

void append_sparkplug(std::string& out, const northbound::sparkplug::SparkplugStats& stats) {
    const auto& session = stats.session;
    out += R"({"group_id":)";
    append_json_string(out, session.group_id);
    append_field(out, "edge_node_id", session.edge_node_id);
    // A node without a primary host waits for none: neither its name nor its state.
    out += R"(,"primary_host":)";
    if (session.primary_host_id.empty()) {
        out += R"(null,"host_online":null)";
    } else {
        append_json_string(out, session.primary_host_id);
        fmt::format_to(std::back_inserter(out), R"(,"host_online":{})", session.host_online);
    }
    fmt::format_to(std::back_inserter(out), R"(,"born":{},"bd_seq":{},"devices":{},)", session.born,
                   session.bd_seq ? std::to_string(*session.bd_seq) : "null", session.devices);
    fmt::format_to(std::back_inserter(out),
                   R"("devices_born":{},"node_births":{},"rebirth_requests":{}}})",
                   session.devices_born, stats.node_births, stats.rebirth_requests);
}

}  // namespace

std::string status_document(const GatewayFacts& facts, const MetricsSources& sources,
                            const Exchanges& exchanges, core::MonoTime now, core::WallTime wall,
                            const WriteLog* writes, std::span<const std::string> warnings) {
    std::string out = R"({"gateway":{"id":)";
    append_json_string(out, facts.id);
    append_field(out, "version", EIP2MQTT_VERSION);
    fmt::format_to(std::back_inserter(out), R"(,"time":{},"started_at":{})", core::to_ms(wall),
                   core::to_ms(facts.started_at));
    out += R"(,"config":{"file":)";
    append_json_string(out, facts.config_file);
    fmt::format_to(std::back_inserter(out), R"(,"loaded_at":{},"reloads":{}}})",
                   core::to_ms(facts.loaded_at), facts.reloads);
    append_mqtt(out, facts.brokers, sources.mqtt);
    append_connections(out, sources);
    out += R"(,"sparkplug":)";
    if (sources.sparkplug != nullptr) {
        append_sparkplug(out, *sources.sparkplug);
    } else {
        out += "null";
    }
    out += R"(,"role":)";
    out += sources.role != nullptr ? sources.role->status_json() : std::string("null");
    out += R"(,"metrics":)";
    out += json_tree::metrics_json(
        sources, std::chrono::duration_cast<std::chrono::seconds>(now - facts.started_mono));
    out += R"(},"exchanges":[)";
    bool first = true;
    for (const auto& consumer : exchanges.consumers()) {
        if (!std::exchange(first, false)) out += ',';
        append_consumer(out, *consumer, now, wall);
        out += '}';
    }
    for (const auto& producer : exchanges.producers()) {
        if (!std::exchange(first, false)) out += ',';
        append_producer(out, *producer);
        out += '}';
    }
    out += ']';
    if (writes != nullptr) {
        out += R"(,"writes":)";
        writes->append_json(out);
        out += R"(,"warnings":[)";
        for (std::size_t i = 0; i < warnings.size(); ++i) {
            if (i != 0) out += ',';
            append_json_string(out, warnings[i]);
        }
        out += ']';
    }
    out += '}';
    return out;
}

std::optional<std::string> exchange_document(const Exchanges& exchanges, std::string_view name,
                                             core::MonoTime now, core::WallTime wall,
                                             const Sparklines* sparklines) {
    std::string out;
    for (const auto& consumer : exchanges.consumers()) {
        if (consumer->plan().spec.name != name) continue;
        append_consumer(out, *consumer, now, wall);
        const auto& exchange = consumer->exchange();
        append_tags(out, consumer->plan(),
                    exchange.has_image() ? exchange.image() : std::span<const std::byte>{},
                    core::quality::quality_of(exchange.state()), consumer->timestamp_ms(),
                    sparklines, core::to_ms(wall));
        return out + '}';
    }
    for (const auto& producer : exchanges.producers()) {
        if (producer->plan().spec.name != name) continue;
        append_producer(out, *producer);
        append_tags(out, producer->plan(), producer->image().data(), core::quality::Quality::good,
                    core::to_ms(wall), nullptr, 0);
        return out + '}';
    }
    return std::nullopt;
}

}  // namespace eip2mqtt::app::status
