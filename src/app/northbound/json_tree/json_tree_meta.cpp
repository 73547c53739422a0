#include "eip2mqtt/app/northbound/json_tree/json_tree_meta.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <nlohmann/json.hpp>

#include "eip2mqtt/app/northbound/json_tree/json_tree_payload.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

// Written out directly rather than built as a JSON tree: a plant's 1,000 exchanges of 100 tags
// are 100,000 tag objects, formatted at every start, and a tree of them cost more than the
// rest of the start-up together.

namespace eip2mqtt::app::northbound::json_tree {
namespace {

using core::plan::Direction;

/// Text from the configuration: names are validated ASCII-safe, but a unit or a description
/// from a point list may be in another encoding; a byte that is not UTF-8 is replaced, never
/// written raw.
void append_text(std::string& out, std::string_view text) {
    const bool ascii = std::all_of(text.begin(), text.end(),
                                   [](char c) { return static_cast<unsigned char>(c) < 0x80; });
    if (ascii) {
        append_json_string(out, text);
    } else {
        out += nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    }
}

void append_text_or_null(std::string& out, std::string_view text) {
    if (text.empty()) {
        out += "null";
    } else {
        append_text(out, text);
    }
}

/// A configured limit: a JSON number that reads as one of floating point (`4000.0`, as a JSON
/// library writes a double), or null when unset.
void append_number(std::string& out, std::optional<double> value) {
    if (!value) {
        out += "null";
        return;
    }
    const auto start = out.size();
    fmt::format_to(std::back_inserter(out), "{}", *value);
    if (out.find_first_of(".eE", start) == std::string::npos) out += ".0";
}

void append_range(std::string& out, const core::plan::ScaleRange& range) {
    out += '[';
    append_number(out, range.lo);
    out += ',';
    append_number(out, range.hi);
    out += ']';
}

/// `"scale":{"kind":"linear","raw":[0.0,32000.0],"eu":[0.0,100.0],"clamp":true,"type_eu":"lreal"}`,
/// or with `"gain"` and `"offset"` for kind gain.
void append_scale(std::string& out, const core::plan::Scaling& scale) {
    fmt::format_to(std::back_inserter(out), R"(,"scale":{{"kind":"{}")",
                   core::plan::to_string(scale.kind));
    if (scale.kind == core::plan::ScaleKind::gain_offset) {
        out += R"(,"gain":)";
        append_number(out, scale.gain);
        out += R"(,"offset":)";
        append_number(out, scale.offset);
    } else {
        out += R"(,"raw":)";
        append_range(out, scale.raw);
        out += R"(,"eu":)";
        append_range(out, scale.eu);
        out += scale.clamp ? R"(,"clamp":true)" : R"(,"clamp":false)";
    }
    fmt::format_to(std::back_inserter(out), R"(,"type_eu":"{}"}})",
                   core::plan::to_string(scale.eu_type.value_or(core::plan::TagType::lreal)));
}

void append_tag(std::string& out, const core::plan::ExchangePlan& plan,
                const core::plan::TagPlan& tag, const core::plan::TopicRebase& rebase,
                std::string& topic) {
    const auto& spec = tag.spec;
    append_text(out, spec.name);
    fmt::format_to(std::back_inserter(out), R"(:{{"type":"{}","address":"{}","topic":)",
                   core::plan::to_string(spec.type), core::plan::to_string(spec.address));
    // Where a consumer finds it, laid out by a template or not.
    plan.tag_topic_into(tag, topic);
    rebase.outward(topic);
    append_text(out, topic);
    out += R"(,"unit":)";
    append_text_or_null(out, spec.unit());
    out += R"(,"description":)";
    append_text_or_null(out, spec.description());
    out += spec.writable ? R"(,"writable":true,"min":)" : R"(,"writable":false,"min":)";
    append_number(out, spec.min());
    out += R"(,"max":)";
    append_number(out, spec.max());
    out += R"(,"deadband":)";
    append_number(out, spec.deadband);
    if (spec.deadband_percent()) {
        out += R"(,"deadband_percent":)";
        append_number(out, spec.deadband_percent());
    }
    if (spec.scale()) append_scale(out, *spec.scale());
    if (spec.publish_raw()) out += R"(,"publish_raw":true)";
    if (spec.type == core::plan::TagType::string) {
        fmt::format_to(std::back_inserter(out), R"(,"length":{})", spec.count);
        if (!spec.trim()) out += R"(,"trim":false)";
    } else if (spec.is_array()) {
        fmt::format_to(std::back_inserter(out), R"(,"count":{})", spec.count);
    }
    out += '}';
}

}  // namespace

std::string format_meta_payload(const core::plan::ExchangePlan& plan,
                                const core::plan::TopicRebase& rebase) {
    const auto& spec = plan.spec;
    const bool consumed = spec.direction == Direction::consume;
    std::string out;
    out.reserve(256 + plan.tags.size() * (160 + plan.topic.size()));
    out += R"({"exchange":)";
    append_text(out, spec.name);
    fmt::format_to(std::back_inserter(out),
                   R"(,"direction":"{}","producer_id":"{}","exchange_id":{},"length":{},)"
                   R"("period_ms":{},"signature":)",
                   core::plan::to_string(spec.direction), core::wire::to_string(spec.producer_id),
                   spec.exchange_id, plan.length, spec.period.count());
    if (spec.signature.is_set()) {
        fmt::format_to(std::back_inserter(out), R"("{}")", core::wire::to_string(spec.signature));
    } else {
        out += "null";
    }
    // Consumed: when the tags turn stale (0: never); produced: where the datagrams go.
    out += R"(,"timeout_ms":)";
    out += consumed ? std::to_string(plan.timeout.count()) : "null";
    out += R"(,"destination":)";
    if (consumed) {
        out += "null";
    } else {
        append_text(out, spec.destination);
    }
    out += R"(,"tags":{)";
    std::string topic;
    for (std::size_t i = 0; i < plan.tags.size(); ++i) {
        if (i > 0) out += ',';
        append_tag(out, plan, plan.tags[i], rebase, topic);
    }
    out += "}}";
    return out;
}

}  // namespace eip2mqtt::app::northbound::json_tree
