// The counter tables against the documents users read: every counter `_status` carries is in
// docs/schema/status.json, in the order the schema requires them, and no counter of the schema
// is missing from the table; the gateway's write and command counters are those of
// docs/schema/metrics.json, keys included, in its order; the Sparkplug node metrics are the ones
// docs/sparkplug.md lists.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "eip2mqtt/app/redundancy/pair_counters.hpp"
#include "eip2mqtt/core/command/command_counters.hpp"
#include "eip2mqtt/core/exchange/consume_counters.hpp"
#include "eip2mqtt/core/exchange/produce_counters.hpp"
#include "eip2mqtt/core/write/write_counters.hpp"

namespace eip2mqtt {
namespace EIP2MQTT_THIS_FILE {

using Names = std::vector<std::string>;

std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

template <class Fields>
Names names_in(const Fields& fields, core::CounterReport report) {
    Names out;
    for (const auto& field : fields) {
        if (field.in(report)) out.emplace_back(field.name);
    }
    return out;
}

/// The properties of `definition` that are counters, in the order of its `required` list.
Names schema_counters(const nlohmann::json& schema, const std::string& definition) {
    const auto& def = schema.at("$defs").at(definition);
    Names out;
    for (const auto& name : def.at("required")) {
        const auto& property = def.at("properties").at(name.get<std::string>());
        if (property.value("$ref", "") == "#/$defs/counter") out.push_back(name);
    }
    return out;
}

TEST(CounterNames, TheConsumedStatusCountersAreTheSchemasInItsOrder) {
    const auto schema = nlohmann::json::parse(read(EIP2MQTT_DOCS_DIR "/schema/status.json"));
    EXPECT_EQ(names_in(core::exchange::consume_counter_fields, core::in_status),
              schema_counters(schema, "consumed"));
}

TEST(CounterNames, TheProducedStatusCountersAreTheSchemasInItsOrder) {
    const auto schema = nlohmann::json::parse(read(EIP2MQTT_DOCS_DIR "/schema/status.json"));
    EXPECT_EQ(names_in(core::exchange::produce_counter_fields, core::in_status),
              schema_counters(schema, "produced"));
}

/// The names of `required` from `first` on, as many as `count`.
Names required_run(const nlohmann::json& object, const std::string& first, std::size_t count) {
    const auto& required = object.at("required");
    Names out;
    for (const auto& name : required) {
        if (out.empty() && name != first) continue;
        if (out.size() < count) out.push_back(name);
    }
    return out;
}

/// What the schema's `object` says of each field of a gateway counter set: a counter for a
/// single count, an object requiring exactly the field's keys, in order, for counts by key.
template <class Fields, class Counters>
void expect_schema_fields(const nlohmann::json& object, const Fields& fields,
                          const Counters& counters) {
    for (const auto& field : fields) {
        if (!field.in(core::in_metrics_topic)) continue;
        const auto& property = object.at("properties").at(std::string(field.name));
        Names keys;
        core::for_each_count(field, counters, [&keys](std::string_view key, std::uint64_t) {
            if (!key.empty()) keys.emplace_back(key);
        });
        if (field.key == nullptr) {
            EXPECT_EQ(property.value("$ref", ""), "#/$defs/counter") << field.name;
        } else {
            EXPECT_EQ(property.at("required").get<Names>(), keys) << field.name;
        }
    }
}

TEST(CounterNames, TheWriteCountersAreTheMetricsSchemasInItsOrder) {
    const auto schema = nlohmann::json::parse(read(EIP2MQTT_DOCS_DIR "/schema/metrics.json"));
    const auto names = names_in(core::write::write_counter_fields, core::in_metrics_topic);
    EXPECT_EQ(required_run(schema, names.front(), names.size()), names);
    expect_schema_fields(schema, core::write::write_counter_fields, core::write::WriteCounters{});
}

TEST(CounterNames, TheCommandCountersAreTheMetricsSchemasInItsOrder) {
    const auto schema = nlohmann::json::parse(read(EIP2MQTT_DOCS_DIR "/schema/metrics.json"));
    const auto& commands =
        schema.at("properties").at(std::string(core::command::command_counters_name));
    EXPECT_EQ(commands.at("required").get<Names>(),
              names_in(core::command::command_counter_fields, core::in_metrics_topic));
    expect_schema_fields(commands, core::command::command_counter_fields,
                         core::command::CommandCounters{});
}

/// The row of docs/sparkplug.md's node metrics table listing `names`.
std::string sparkplug_row(const Names& names, const std::string& direction) {
    std::string row = "`Exchanges/{exchange}/" + names.front() + "`";
    for (std::size_t i = 1; i < names.size(); ++i) row += ", `" + names[i] + "`";
    return row + " (" + direction + ")";
}

TEST(CounterNames, ThePairCountersAreTheMetricsSchemasInItsOrder) {
    const auto schema = nlohmann::json::parse(read(EIP2MQTT_DOCS_DIR "/schema/metrics.json"));
    const auto& pair = schema.at("properties").at("pair");
    EXPECT_EQ(pair.at("required").get<Names>(),
              names_in(app::redundancy::pair_counter_fields, core::in_metrics_topic));
    expect_schema_fields(pair, app::redundancy::pair_counter_fields,
                         app::redundancy::PairCounters{});
}

TEST(CounterNames, TheExchangeNodeMetricsAreTheOnesTheSparkplugPageLists) {
    const auto page = read(EIP2MQTT_DOCS_DIR "/sparkplug.md");
    const auto consumed = sparkplug_row(
        names_in(core::exchange::consume_counter_fields, core::in_sparkplug), "consumed");
    EXPECT_NE(page.find(consumed), std::string::npos) << consumed;
    const auto produced = sparkplug_row(
        names_in(core::exchange::produce_counter_fields, core::in_sparkplug), "produced");
    EXPECT_NE(page.find(produced), std::string::npos) << produced;
}

TEST(CounterNames, TheGatewaysWriteNodeMetricsAreTheOnesTheSparkplugPageLists) {
    const auto page = read(EIP2MQTT_DOCS_DIR "/sparkplug.md");
    std::string row = "`Gateway/dropped`";
    for (const auto& name : names_in(core::write::write_counter_fields, core::in_sparkplug)) {
        row += ", `Gateway/" + name + "`";
    }
    EXPECT_NE(page.find(row + " |"), std::string::npos) << row;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt
