// Whether a reloaded file may be applied: refused whole for its errors or for a key only a
// restart applies, else accepted with the changes it makes.

#include "eip2mqtt/app/reload/reload_check.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/reload/reload_sequence.hpp"

namespace eip2mqtt::app::reload {
namespace EIP2MQTT_THIS_FILE {

/// A file with only `id` and `level` set, parsed and planned as a reload does.
ParseResult file_with(const std::string& id, const std::string& level) {
    const auto text = "gateway:\n  id: " + id + "\n  state_dir: /tmp/eip2mqtt-test\n" +
                      "  log_level: " + level + "\nmqtt:\n  url: tcp://127.0.0.1:1883\n" +
                      "exchanges:\n  - name: a\n    direction: consume\n" +
                      "    producer_id: 10.0.0.1\n    exchange_id: 1\n    length: 4\n" +
                      "    tags:\n      - { name: T, address: \"0.0\", type: dint }\n";
    auto loaded = adapters::yaml::load_config_text(text, "gateway.yaml");
    if (!loaded) return core::fail(loaded.error());
    ParsedConfig parsed{std::move(loaded).value(), {}};
    parsed.plans = take_plans(parsed.config);
    return parsed;
}

/// The plans the running gateway of `running` runs.
std::vector<const core::plan::ExchangePlan*> plans_of(const ParseResult& running) {
    std::vector<const core::plan::ExchangePlan*> out;
    for (const auto& plan : running->plans) out.push_back(&plan);
    return out;
}

TEST(ReloadCheck, AcceptsALiveChangeNamingIt) {
    const auto running = file_with("gw", "info");
    const auto changes = accept(file_with("gw", "debug"), running->config, plans_of(running));
    ASSERT_TRUE(changes.has_value());
    EXPECT_FALSE(changes->needs_restart);
    EXPECT_EQ(changes->describe(core::config::ReloadRule::live), "gateway.log_level");
}

TEST(ReloadCheck, AcceptsTheSameFileAsNoChange) {
    const auto running = file_with("gw", "info");
    const auto changes = accept(file_with("gw", "info"), running->config, plans_of(running));
    ASSERT_TRUE(changes.has_value());
    EXPECT_TRUE(changes->empty());
}

TEST(ReloadCheck, RefusesAKeyOnlyARestartApplies) {
    const auto running = file_with("gw", "info");
    EXPECT_FALSE(accept(file_with("other", "debug"), running->config, plans_of(running)));
}

TEST(ReloadCheck, RefusesAFileWithErrors) {
    const auto running = file_with("gw", "info");
    const auto broken = file_with("gw", "loud");  // not a log level
    ASSERT_FALSE(broken);
    EXPECT_FALSE(accept(broken, running->config, plans_of(running)));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::reload
