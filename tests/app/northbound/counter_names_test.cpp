// The counter tables against the documents users read: every counter `_status` carries is in
// docs/schema/status.json, in the order the schema requires them, and no counter of the schema
// is missing from the table; the Sparkplug node metrics are the ones docs/sparkplug.md lists.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "eip2mqtt/core/exchange/consume_counters.hpp"
#include "eip2mqtt/core/exchange/produce_counters.hpp"

namespace eip2mqtt {
namespace {

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

/// The row of docs/sparkplug.md's node metrics table listing `names`.
std::string sparkplug_row(const Names& names, const std::string& direction) {
    std::string row = "`Exchanges/{exchange}/" + names.front() + "`";
    for (std::size_t i = 1; i < names.size(); ++i) row += ", `" + names[i] + "`";
    return row + " (" + direction + ")";
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

}  // namespace
}  // namespace eip2mqtt
