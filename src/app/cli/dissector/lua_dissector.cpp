#include "eip2mqtt/app/cli/dissector/lua_dissector.hpp"

#include <fmt/format.h>

#include <string_view>

#include "app/cli/dissector/detail/lua_runtime.hpp"
#include "eip2mqtt/app/cli/dissector/field_names.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app::dissector {
namespace {

using core::plan::ExchangePlan;

/// Field-name parts no exchange may take: the expert entries live under eip2mqtt.expert.
const std::unordered_set<std::string> reserved_exchange_parts{"expert"};

std::string tag_label(const core::plan::TagSpec& tag) {
    if (tag.scale()) return tag.name + " (raw)";
    if (tag.unit().empty()) return tag.name;
    return tag.name + " (" + tag.unit() + ")";
}

std::string lua_number(double value) {
    // %.17g reads back as the same double; Lua 5.2 reads numbers as doubles.
    return fmt::format("{:.17g}", value);
}

/// The scale's Lua table and its engineering field's label, as arguments of `tag(...)`.
std::string scale_arguments(const core::plan::TagSpec& tag) {
    const auto& s = *tag.scale();
    std::string table = "{ kind = \"" + std::string(core::plan::to_string(s.kind)) + "\"";
    if (s.kind == core::plan::ScaleKind::gain_offset) {
        table += ", gain = " + lua_number(s.gain) + ", offset = " + lua_number(s.offset);
    } else {
        table += ", raw = { " + lua_number(s.raw.lo) + ", " + lua_number(s.raw.hi) + " }, eu = { " +
                 lua_number(s.eu.lo) + ", " + lua_number(s.eu.hi) + " }" +
                 (s.clamp ? ", clamp = true" : "");
    }
    const std::string label = tag.unit().empty() ? tag.name : tag.name + " (" + tag.unit() + ")";
    return ", " + table + " }, " + lua_string(label);
}

/// The key the plugin looks exchanges up by: "producer id/exchange id", as its dissector
/// builds it from the header.
std::string exchange_key(const ExchangePlan& plan) {
    return core::wire::to_string(plan.spec.producer_id) + "/" +
           std::to_string(plan.spec.exchange_id);
}

std::string exchange_table(const ExchangePlan& plan) {
    std::string table = "{ key = " + lua_string(exchange_key(plan)) +
                        ", name = " + lua_string(plan.spec.name) +
                        ", length = " + std::to_string(plan.length);
    if (plan.spec.signature.is_set()) {
        table += ", signature = { " + std::to_string(plan.spec.signature.major) + ", " +
                 std::to_string(plan.spec.signature.minor) + " }";
    }
    table += ", period_ms = " + std::to_string(plan.spec.period.count()) +
             ", timeout_ms = " + std::to_string(plan.timeout.count()) +
             ", clock_tolerance_ms = " + std::to_string(plan.clock_tolerance.count()) + " }";
    return table;
}

/// One `exchange(...)` call. Its tags are defined in a function of their own, so that each
/// exchange's names are constants of that function: a plant's 100,000 tags never crowd one
/// Lua function's constant table.
void append_exchange(const ExchangePlan& plan, const std::string& part, std::string& out) {
    out += "exchange(" + exchange_table(plan) + ", function(tag)\n";
    FieldParts tag_parts;
    for (const auto& tag : plan.tags) {
        const auto& spec = tag.spec;
        out += "  tag(" + lua_string("eip2mqtt." + part + "." + tag_parts.unique(spec.name)) +
               ", " + lua_string(tag_label(spec)) + ", \"" +
               std::string(core::plan::to_string(spec.type)) + "\", " +
               std::to_string(spec.address.byte) + ", " + std::to_string(spec.address.bit) +
               (spec.scale() ? scale_arguments(spec)
                             : std::string(spec.count > 1 ? ", nil, nil" : "")) +
               (spec.count > 1 ? ", " + std::to_string(spec.count) : std::string()) + ")\n";
    }
    out += "end)\n";
}

}  // namespace

std::string lua_dissector(const std::vector<ExchangePlan>& plans,
                          const DissectorSettings& settings) {
    std::string out =
        "-- eip2mqtt.lua: a Wireshark plugin (Lua 5.2) written by `eip2mqtt dissector` from\n"
        "-- the configuration " +
        lua_string(settings.source) +
        ". Write it again when the configuration changes.\n"
        "-- Install it in ~/.local/lib/wireshark/plugins/, or load it once with\n"
        "-- `tshark -X lua_script:eip2mqtt.lua`.\n"
        "local settings = { data_port = " +
        std::to_string(settings.data_port) +
        ", command_port = " + std::to_string(settings.command_port) +
        ", clock_tolerance_ms = " + std::to_string(settings.clock_tolerance.count()) + " }\n";
    out += detail::lua_prelude;
    out += "\n";
    FieldParts exchange_parts(reserved_exchange_parts);
    for (const auto& plan : plans) {
        append_exchange(plan, exchange_parts.unique(plan.spec.name), out);
    }
    out += detail::lua_statistics;
    out += detail::lua_dissection;
    out += detail::lua_commands;
    return out;
}

}  // namespace eip2mqtt::app::dissector
