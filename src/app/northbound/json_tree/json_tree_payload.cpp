#include "eip2mqtt/app/northbound/json_tree/json_tree_payload.hpp"

#include <fmt/format.h>

#include <iterator>
#include <nlohmann/json.hpp>

#include "eip2mqtt/app/health/metrics.hpp"
#include "eip2mqtt/app/northbound/json_tree/counter_json.hpp"
#include "eip2mqtt/app/redundancy/role_metrics.hpp"
#include "eip2mqtt/core/json_text.hpp"
#include "eip2mqtt/core/plan/published_value.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app::northbound::json_tree {

namespace {

using core::config::PayloadFormat;

/// The opening of a Kepware payload, up to its `values` list: `{"timestamp":…,"values":[`.
void append_kepware_head(std::string& out, std::int64_t timestamp_ms) {
    out += R"({"timestamp":)";
    core::append_integer(out, timestamp_ms);
    out += R"(,"values":[)";
}

/// One entry of Kepware's `values`: `{"id":"exchange.tag","v":…,"q":true,"t":…}`.
void append_kepware_value(std::string& out, std::string_view exchange, std::string_view tag,
                          const core::plan::Value& value, core::quality::Quality quality,
                          std::int64_t timestamp_ms) {
    std::string id;
    id.reserve(exchange.size() + 1 + tag.size());
    id.append(exchange).append(".").append(tag);
    out += R"({"id":)";
    append_json_string(out, id);
    out += R"(,"v":)";
    core::plan::append_json(out, value);
    out += quality == core::quality::Quality::good ? R"(,"q":true,"t":)" : R"(,"q":false,"t":)";
    core::append_integer(out, timestamp_ms);
    out += '}';
}

}  // namespace

void format_tag_payload(std::string& out, std::string_view exchange, const core::plan::TagSpec& tag,
                        const core::plan::Value& raw, core::quality::Quality quality,
                        std::int64_t timestamp_ms, PayloadFormat format) {
    out.clear();
    const auto published = core::plan::published_value(tag, raw);
    switch (format) {
        case PayloadFormat::raw:
            out = core::plan::to_json(published.value);
            return;
        case PayloadFormat::value:
            // Text as it is: a dashboard shows `B-12`, not `"B-12"`.
            if (const auto* text = std::get_if<core::plan::Text>(&published.value)) {
                out = **text;
            } else {
                out = core::plan::to_json(published.value);
            }
            return;
        case PayloadFormat::umh:
            out += R"({"value":)";
            core::plan::append_json(out, published.value);
            out += R"(,"timestamp_ms":)";
            core::append_integer(out, timestamp_ms);
            out += '}';
            return;
        case PayloadFormat::kepware:
            append_kepware_head(out, timestamp_ms);
            append_kepware_value(out, exchange, tag.name, published.value, quality, timestamp_ms);
            out += "]}";
            return;
        case PayloadFormat::json:
            break;
    }
    // Appended piece by piece, not through a format string: under overload this runs for
    // every tag change, several times for each publication the broker takes.
    out += R"({"value":)";
    core::plan::append_json(out, published.value);
    out += R"(,"timestamp":)";
    core::append_integer(out, timestamp_ms);
    out += R"(,"quality":")";
    out += core::quality::to_string(quality);
    out += '"';
    if (published.limit != core::plan::Limit::none) {
        out += R"(,"limit":")";
        out += core::plan::to_string(published.limit);
        out += '"';
    }
    if (tag.publish_raw()) {
        out += R"(,"raw":)";
        core::plan::append_json(out, raw);
    }
    out += '}';
}

void format_values_payload(std::string& out, const SampleBatch& batch, PayloadFormat format) {
    out.clear();
    if (format == PayloadFormat::kepware) {
        append_kepware_head(out, batch.timestamp_ms);
        bool first = true;
        for (const auto& sample : batch.samples) {
            if (!first) out += ',';
            first = false;
            const auto& tag = batch.exchange.tags[sample.tag].spec;
            append_kepware_value(out, batch.exchange.spec.name, tag.name,
                                 core::plan::published_value(tag, sample.value).value,
                                 batch.quality, batch.timestamp_ms);
        }
        out += "]}";
        return;
    }
    fmt::format_to(std::back_inserter(out), R"({{"timestamp":{},"quality":"{}","values":{{)",
                   batch.timestamp_ms, core::quality::to_string(batch.quality));
    bool first = true;
    for (const auto& sample : batch.samples) {
        if (!first) out += ',';
        first = false;
        const auto& tag = batch.exchange.tags[sample.tag].spec;
        append_json_string(out, tag.name);
        out += ':';
        core::plan::append_json(out, core::plan::published_value(tag, sample.value).value);
    }
    out += "}}";
}

void add_data_properties(adapters::mqtt::Message& message,
                         std::span<const core::config::MessageProperty> chosen,
                         const core::plan::ExchangePlan& plan, const core::plan::TagSpec* tag,
                         core::quality::Quality quality, std::int64_t timestamp_ms) {
    using core::config::MessageProperty;
    for (const auto property : chosen) {
        const auto name = core::config::message_property_names.name_of(property);
        switch (property) {
            case MessageProperty::unit:
                if (tag && !tag->unit().empty()) {
                    adapters::mqtt::add_user_property(message, name, tag->unit());
                }
                break;
            case MessageProperty::quality:
                adapters::mqtt::add_user_property(message, name, core::quality::to_string(quality));
                break;
            case MessageProperty::source_time:
                adapters::mqtt::add_user_property(message, name, std::to_string(timestamp_ms));
                break;
            case MessageProperty::exchange:
                adapters::mqtt::add_user_property(message, name, plan.spec.name);
                break;
            case MessageProperty::producer:
                adapters::mqtt::add_user_property(message, name,
                                                  core::wire::to_string(plan.spec.producer_id));
                break;
        }
    }
}

std::string format_status_payload(const ConsumedStatus& status) {
    const auto& exchange = status.state;
    const auto& clock = status.clock;
    const auto& last_seen_ms = status.last_seen_ms;
    const auto& c = exchange.counters();
    std::string out;
    auto to = std::back_inserter(out);
    fmt::format_to(to, R"({{"state":"{}","request_id":)",
                   core::exchange::to_string(exchange.state()));
    if (exchange.has_image()) {
        fmt::format_to(to, "{}", exchange.last_header().request_id);
    } else {
        out += "null";
    }
    for (const auto& field : core::exchange::consume_counter_fields) {
        if (field.in(core::in_status))
            fmt::format_to(to, R"(,"{}":{})", field.name, c.*field.member);
    }
    out += R"(,"last_seen":)";
    out += last_seen_ms ? std::to_string(*last_seen_ms) : "null";
    fmt::format_to(to, R"(,"clock":"{}","clock_offset_ms":)",
                   core::exchange::to_string(clock.state()));
    out += clock.offset_ms() ? std::to_string(*clock.offset_ms()) : "null";
    out += '}';
    return out;
}

std::string format_produced_status_payload(const ProducedStatus& status) {
    std::string out;
    auto to = std::back_inserter(out);
    fmt::format_to(to, R"({{"state":"{}","request_id":{})", status.paused ? "paused" : "producing",
                   status.request_id);
    for (const auto& field : core::exchange::produce_counter_fields) {
        if (field.in(core::in_status)) {
            fmt::format_to(to, R"(,"{}":{})", field.name, status.counters.*field.member);
        }
    }
    fmt::format_to(to, R"(,"writes_pending":{},"saved":{},"save_error":)", status.writes_pending,
                   status.saved);
    if (status.save_error.empty()) {
        out += "null";
    } else {
        // A system's message and a path, which may hold anything: escaped, and any byte that
        // is not UTF-8 replaced.
        out += nlohmann::json(status.save_error)
                   .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }
    out += '}';
    return out;
}

std::string format_write_result(std::optional<std::string_view> error) {
    if (!error) return R"({"ok":true})";
    const nlohmann::json result = {{"ok", false}, {"error", *error}};
    return result.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string format_write_result_unsaved(std::string_view reason) {
    const nlohmann::json result = {
        {"ok", true}, {"saved", false}, {"error", "not saved: " + std::string(reason)}};
    return result.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

std::string metrics_json(const MetricsSources& sources, std::chrono::seconds uptime) {
    const auto& mqtt = sources.mqtt;
    nlohmann::json metrics = {
        {"uptime_s", uptime.count()},
        {"datagrams", sources.datagrams.datagrams},
        {"accepted", sources.datagrams.accepted},
        {"dropped", drops_by_name(sources.datagrams)},
        {"published", mqtt.published},
        {"buffered", mqtt.queued},
        {"publications_dropped", mqtt.dropped_overflow},
        {"publications_coalesced", mqtt.coalesced},
        {"publications_refused", mqtt.refused},
        {"mqtt_connects", mqtt.connects},
        {"broker", mqtt.broker},
    };
    add_counter_set(metrics, core::write::write_counter_fields, sources.writes);
    redundancy::add_role_metrics(metrics, sources);
    if (sources.commands) {
        add_counter_set(metrics[std::string(core::command::command_counters_name)],
                        core::command::command_counter_fields, *sources.commands);
    }
    if (sources.history) {
        const auto h = history_metrics(*sources.history);
        metrics["history_dropped"] = h.dropped;
        metrics["history"] = {
            {"entries", h.entries},
            {"bytes", h.bytes},
            {"oldest_age_s", h.oldest_age_seconds},
            {"journaled", h.journaled},
            {"replayed", h.replayed},
            {"discarded", h.discarded},
            {"replaying", h.replaying},
        };
    }
    if (sources.sparkplug) {
        const auto& sp = *sources.sparkplug;
        metrics["sparkplug"] = {{"births_refused", sp.births_refused},
                                {"data_refused", sp.data_refused},
                                {"rebirth_requests", sp.rebirth_requests},
                                {"node_births", sp.node_births}};
    }
    return metrics.dump();
}

}  // namespace eip2mqtt::app::northbound::json_tree
