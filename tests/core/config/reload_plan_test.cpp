// What a reload changes, named key by key with its rule (docs/operations.md,
// Reload). tests/adapters/yaml/config_keys_test.cpp walks every key of the file; these are the
// plan's own rules: matching by name, additions and removals, tag order, the cap on names.

#include "eip2mqtt/core/config/reload_plan.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using Kind = KeyChange::Kind;
using plan::ExchangePlan;

ExchangePlan exchange(std::string name, std::vector<std::string> tag_names) {
    plan::ExchangeSpec spec;
    spec.name = name;
    spec.topic = std::move(name);
    std::uint16_t byte = 0;
    for (auto& tag_name : tag_names) {
        plan::TagSpec tag;
        tag.name = std::move(tag_name);
        tag.address = {byte, 0};
        tag.type = plan::TagType::int_;
        spec.tags.push_back(std::move(tag));
        byte += 2;
    }
    return plan::make_exchange_plan(std::move(spec), "plant");
}

ReloadPlan plan_of(const Config& running, const std::vector<ExchangePlan>& before,
                   const Config& next, const std::vector<ExchangePlan>& after) {
    std::vector<const ExchangePlan*> pointers;
    for (const auto& p : before) pointers.push_back(&p);
    return plan_reload(running, pointers, next, after);
}

ReloadPlan plan_of(const std::vector<ExchangePlan>& before,
                   const std::vector<ExchangePlan>& after) {
    return plan_of(Config{}, before, Config{}, after);
}

TEST(ReloadPlan, NothingChangedNamesNothing) {
    const std::vector running{exchange("a", {"X", "Y"})};
    const auto plan = plan_of(running, running);
    EXPECT_TRUE(plan.empty());
    EXPECT_FALSE(plan.needs_restart);
}

TEST(ReloadPlan, ASectionKeyIsNamedWithItsRule) {
    Config next;
    next.mqtt.urls = {"tcp://localhost:1883", "tcp://elsewhere:1883"};
    next.mqtt.qos = 0;
    const auto plan = plan_of(Config{}, {}, next, {});
    EXPECT_EQ(plan.changes, (std::vector<KeyChange>{{"mqtt.url", ReloadRule::restart},
                                                    {"mqtt.qos", ReloadRule::live}}));
    EXPECT_TRUE(plan.needs_restart);
    EXPECT_EQ(plan.describe(ReloadRule::restart), "mqtt.url");
    EXPECT_EQ(plan.describe(ReloadRule::live), "mqtt.qos");
}

TEST(ReloadPlan, AnotherConnectionsKeysAreNamedByItsName) {
    Config running;
    running.more_mqtt.push_back({});
    running.more_mqtt[0].name = "enterprise";
    Config next = running;
    next.more_mqtt[0].qos = 0;
    next.more_mqtt[0].base_topic = "acme";
    const auto plan = plan_of(running, {}, next, {});
    EXPECT_EQ(plan.changes,
              (std::vector<KeyChange>{{"mqtt[enterprise].base_topic", ReloadRule::restart},
                                      {"mqtt[enterprise].qos", ReloadRule::live}}));
    // A connection more or less is a restart.
    const auto added = plan_of(Config{}, {}, running, {});
    EXPECT_EQ(added.changes, (std::vector<KeyChange>{{"mqtt", ReloadRule::restart}}));
    EXPECT_TRUE(added.needs_restart);
}

TEST(ReloadPlan, TlsIsNamedWholeWhenAddedAndByKeyWhenBothHaveIt) {
    Config with_tls;
    with_tls.mqtt.tls = TlsSection{"/etc/ca.pem", "", "", true};
    EXPECT_EQ(plan_of(Config{}, {}, with_tls, {}).changes,
              (std::vector<KeyChange>{{"mqtt.tls", ReloadRule::restart}}));
    Config other_ca = with_tls;
    other_ca.mqtt.tls->ca_file = "/etc/other-ca.pem";
    EXPECT_EQ(plan_of(with_tls, {}, other_ca, {}).changes,
              (std::vector<KeyChange>{{"mqtt.tls.ca_file", ReloadRule::restart}}));
}

TEST(ReloadPlan, AMulticastGroupChangeIsAChangeOfTheList) {
    Config running;
    running.eip.multicast = {{"239.1.1.1", ""}};
    Config next;
    next.eip.multicast = {{"239.1.1.1", "eth1"}};
    EXPECT_EQ(plan_of(running, {}, next, {}).changes,
              (std::vector<KeyChange>{{"eip.multicast", ReloadRule::live}}));
}

TEST(ReloadPlan, ExchangesAndTagsAreMatchedByName) {
    const std::vector running{exchange("kept", {"X"}), exchange("changed", {"A", "B"}),
                              exchange("gone", {"X"})};
    auto changed = exchange("changed", {"A", "C"});
    changed.tags[0].spec.deadband = 0.5;
    const std::vector next{exchange("new", {"X"}), changed, exchange("kept", {"X"})};
    const auto plan = plan_of(running, next);
    EXPECT_EQ(plan.changes, (std::vector<KeyChange>{
                                {"exchanges[new]", ReloadRule::live, Kind::added},
                                {"exchanges[changed].tags[A].deadband", ReloadRule::live},
                                {"exchanges[changed].tags[C]", ReloadRule::live, Kind::added},
                                {"exchanges[changed].tags[B]", ReloadRule::live, Kind::removed},
                                {"exchanges[gone]", ReloadRule::live, Kind::removed},
                            }));
    EXPECT_FALSE(plan.needs_restart);
    EXPECT_EQ(plan.describe(ReloadRule::live),
              "exchanges[new] (added), exchanges[changed].tags[A].deadband, "
              "exchanges[changed].tags[C] (added), exchanges[changed].tags[B] (removed), "
              "exchanges[gone] (removed)");
}

TEST(ReloadPlan, TheSameTagsInAnotherOrderAreNamedAsTheExchangesTags) {
    const std::vector running{exchange("a", {"X", "Y"})};
    auto swapped = exchange("a", {"X", "Y"});
    std::swap(swapped.tags[0], swapped.tags[1]);
    EXPECT_EQ(plan_of(running, {swapped}).changes,
              (std::vector<KeyChange>{{"exchanges[a].tags", ReloadRule::live}}));
}

TEST(ReloadPlan, PlansChangedByASectionAloneNameOnlyTheSectionsKey) {
    // gateway.timestamp resolves into every consumed exchange that does not set its own.
    Config next;
    next.gateway.exchange_defaults.timestamp = plan::TimestampSource::receive;
    const std::vector running{exchange("a", {"X"})};
    auto resolved = exchange("a", {"X"});
    resolved.timestamp = plan::TimestampSource::receive;
    EXPECT_EQ(plan_of(Config{}, running, next, {resolved}).changes,
              (std::vector<KeyChange>{{"gateway.timestamp", ReloadRule::live}}));
}

TEST(ReloadPlan, BeyondTheCapChangesAreCountedNotNamed) {
    std::vector<std::string> names;
    for (int i = 0; i < 60; ++i) names.push_back("T" + std::to_string(i));
    const std::vector running{exchange("a", names)};
    auto next = exchange("a", names);
    for (auto& tag : next.tags) tag.spec.deadband = 1;
    Config restart;
    restart.metrics.listen = "127.0.0.1:9108";
    const auto plan = plan_of(Config{}, running, restart, {next});
    ASSERT_EQ(plan.changes.size(), ReloadPlan::max_named);
    EXPECT_EQ(plan.unnamed, 61 - ReloadPlan::max_named);
    EXPECT_EQ(plan.changes.front(), (KeyChange{"metrics.listen", ReloadRule::restart}));
    EXPECT_TRUE(plan.needs_restart);
    const auto live = plan.describe(ReloadRule::live);
    EXPECT_EQ(live.substr(0, 32), "exchanges[a].tags[T0].deadband, ");
    EXPECT_EQ(live.substr(live.size() - 13), ", and 11 more");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
