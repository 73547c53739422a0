// Every key of the configuration file has a reload rule, and a reload names a change to it
// (docs/operations.md, Reload). The loader accepts exactly the keys of
// core/config/config_keys.hpp; here each of them is changed alone in a file that writes every
// key, and core::config::plan_reload must name that key, and nothing else, with its rule. A key
// added to the table without an edit here fails EveryKeyOfTheTableIsEditedHere; one the loader
// reads but the plan does not compare fails AChangeToAnyKeyIsNamedAloneWithItsRule.

#include "eip2mqtt/core/config/config_keys.hpp"

#include <gtest/gtest.h>

#include <map>
#include <set>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/core/config/reload_plan.hpp"
#include "tests/adapters/yaml/config_key_edits.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

namespace keys = core::config::keys;
using core::config::Config;
using core::config::ReloadRule;
using Kind = core::config::KeyChange::Kind;

using test_keys::complete;
using test_keys::Edit;
using test_keys::every_edit;
using test_keys::points;

/// The keys whose value is a mapping or a list of mappings: edited through their own keys.
const std::set<std::string> mapping_keys = {"mqtt.buffer", "mqtt.store_and_forward", "eip.commands",
                                            "exchanges[].tags"};

/// Every other key of the table, with its rule, by the table's name.
std::map<std::string, ReloadRule> table_keys() {
    std::map<std::string, ReloadRule> out;
    const auto add = [&](const std::string& prefix, const auto& table) {
        for (const auto& key : table) {
            const auto name = prefix + std::string(key.name);
            if (!mapping_keys.contains(name)) out.emplace(name, key.rule);
        }
    };
    add("gateway.", keys::gateway);
    add("mqtt.", keys::mqtt);
    add("mqtt.tls.", keys::tls);
    add("mqtt.buffer.", keys::buffer);
    add("mqtt.store_and_forward.", keys::store_and_forward);
    add("eip.", keys::eip);
    add("eip.multicast.", keys::multicast);
    add("eip.commands.", keys::commands);
    add("metrics.", keys::metrics);
    add("sparkplug.", keys::sparkplug);
    add("redundancy.", keys::redundancy);
    add("exchanges[].", keys::exchange);
    add("exchanges[].tags[].", keys::tag);
    return out;
}

class ConfigKeys : public ::testing::Test {
protected:
    ConfigKeys() {
        dir_.write("points-a.csv", points);
        dir_.write("points-b.csv", points);
    }

    Config load(const std::string& text) const {
        auto result = load_config_text(text, dir_.path() + "/gateway.yaml");
        std::string errors;
        if (!result.ok()) {
            for (const auto& d : result.error()) errors += d.to_string() + "\n";
        }
        EXPECT_TRUE(result.ok()) << errors;
        return result.ok() ? std::move(result).value() : Config{};
    }

    core::config::ReloadPlan plan(const Config& running, const Config& next) const {
        const auto running_plans = core::config::make_plans(running);
        const auto next_plans = core::config::make_plans(next);
        std::vector<const core::plan::ExchangePlan*> pointers;
        for (const auto& p : running_plans) pointers.push_back(&p);
        return core::config::plan_reload(running, pointers, next, next_plans);
    }

    test::TempDir dir_;
};

TEST_F(ConfigKeys, EveryKeyOfTheTableIsEditedHere) {
    std::set<std::string> table;
    for (const auto& [key, rule] : table_keys()) table.insert(key);
    std::set<std::string> edited;
    for (const auto& edit : every_edit()) EXPECT_TRUE(edited.insert(edit.key).second) << edit.key;
    EXPECT_EQ(edited, table);
}

TEST_F(ConfigKeys, TheCompleteFileNamesNothingAgainstItself) {
    const auto config = load(complete);
    ASSERT_EQ(config.exchanges.size(), 3u);
    ASSERT_EQ(config.exchanges[0].tags.size(), 3u);  // SPEED, TEXT, then the point list's FLOW
    EXPECT_TRUE(plan(config, load(complete)).empty());
}

TEST_F(ConfigKeys, AChangeToAnyKeyIsNamedAloneWithItsRule) {
    const auto rules = table_keys();
    const auto running = load(complete);
    for (const auto& edit : every_edit()) {
        SCOPED_TRACE(edit.key);
        const auto at = complete.find(edit.from);
        ASSERT_NE(at, std::string::npos);
        ASSERT_EQ(complete.find(edit.from, at + 1), std::string::npos) << "found twice";
        auto text = complete;
        text.replace(at, edit.from.size(), edit.to);
        if (!edit.refused.empty()) {
            const auto result = load_config_text(text, dir_.path() + "/gateway.yaml");
            ASSERT_FALSE(result.ok());
            std::string errors;
            for (const auto& d : result.error()) errors += d.to_string() + "\n";
            EXPECT_NE(errors.find(edit.refused), std::string::npos) << errors;
            continue;
        }

        const auto changes = plan(running, load(text));
        const auto found = rules.find(edit.key);
        ASSERT_NE(found, rules.end()) << "not a key of the table";
        const auto rule = found->second;
        std::vector<std::pair<std::string, Kind>> named;
        for (const auto& change : changes.changes) {
            named.emplace_back(change.key, change.kind);
            EXPECT_EQ(change.rule, rule) << change.key;
        }
        const auto expected =
            edit.named.empty()
                ? std::vector<std::pair<std::string, Kind>>{{edit.key, Kind::changed}}
                : edit.named;
        EXPECT_EQ(named, expected);
        EXPECT_EQ(changes.needs_restart, rule == ReloadRule::restart);
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
