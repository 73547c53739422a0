// `eip.commands` (docs/protocol.md §9; docs/commissioning.md): the responder's settings, their
// defaults, and the errors a wrong value gets.

#include <gtest/gtest.h>

#include <string>

#include "eip2mqtt/adapters/yaml/load_config.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

const std::string exchange =
    "exchanges:\n"
    "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n";

std::string errors_of(const std::string& text) {
    const auto result = load_config_text(text + exchange, "test.yaml");
    EXPECT_FALSE(result.ok());
    std::string out;
    if (result.ok()) return out;
    for (const auto& d : result.error()) {
        out += std::to_string(d.mark.line) + ":" + std::to_string(d.mark.column) + ": " +
               d.message + "\n";
    }
    return out;
}

core::config::CommandsSection commands_of(const std::string& text) {
    const auto result = load_config_text(text + exchange, "test.yaml");
    EXPECT_TRUE(result.ok());
    return result.ok() ? result.value().eip.commands : core::config::CommandsSection{};
}

TEST(CommandsConfig, OffByDefaultOnPort7937WithoutWrites) {
    const auto commands = commands_of("");
    EXPECT_FALSE(commands.enabled);
    EXPECT_EQ(commands.port, 7937);
    EXPECT_FALSE(commands.allow.has_value());  // the subnets of eip.bind, resolved at start
    EXPECT_TRUE(commands.trusted.empty());
    EXPECT_FALSE(commands.writes);
    EXPECT_EQ(commands.max_requests_per_s, 100u);
    EXPECT_EQ(commands.max_requests_per_s_per_source, 20u);
}

TEST(CommandsConfig, EveryKeyIsRead) {
    const auto commands = commands_of(
        "eip:\n"
        "  commands:\n"
        "    enabled: true\n"
        "    port: 17937\n"
        "    allow: [ 10.20.0.7/24, 192.168.1.5 ]\n"
        "    writes: true\n"
        "    max_requests_per_s: 20\n"
        "    trusted: [ 10.20.0.9 ]\n"
        "    max_requests_per_s_per_source: 5\n");
    EXPECT_TRUE(commands.enabled);
    EXPECT_EQ(commands.port, 17937);
    ASSERT_TRUE(commands.allow.has_value());
    ASSERT_EQ(commands.allow->size(), 2u);
    EXPECT_EQ(core::net::to_string((*commands.allow)[0]), "10.20.0.0/24");
    EXPECT_EQ(core::net::to_string((*commands.allow)[1]), "192.168.1.5/32");
    EXPECT_TRUE(commands.writes);
    EXPECT_EQ(commands.max_requests_per_s, 20u);
    ASSERT_EQ(commands.trusted.size(), 1u);
    EXPECT_EQ(core::net::to_string(commands.trusted[0]), "10.20.0.9/32");
    EXPECT_EQ(commands.max_requests_per_s_per_source, 5u);
}

TEST(CommandsConfig, AllowWrittenEmptyIsNobodyNotTheDefault) {
    const auto commands = commands_of("eip:\n  commands: { enabled: true, allow: [] }\n");
    ASSERT_TRUE(commands.allow.has_value());
    EXPECT_TRUE(commands.allow->empty());
}

TEST(CommandsConfig, WrongTrustedAndPerSourceValuesAreNamedWhereTheyAre) {
    const auto text = errors_of(
        "eip:\n"
        "  commands:\n"
        "    trusted: [ 10.20.0.0/40 ]\n"
        "    max_requests_per_s_per_source: 0\n"
        "    allow: 10.0.0.0/8\n");
    EXPECT_NE(text.find("3:16: trusted '10.20.0.0/40' is not an IPv4 subnet"), std::string::npos)
        << text;
    EXPECT_NE(text.find("4:5: 'max_requests_per_s_per_source' 0 is outside 1.."), std::string::npos)
        << text;
    EXPECT_NE(text.find("5:5: expected a list of subnets for 'allow'"), std::string::npos) << text;
}

TEST(CommandsConfig, WrongValuesAreNamedWhereTheyAre) {
    const auto text = errors_of(
        "eip:\n"
        "  commands:\n"
        "    enabled: sometimes\n"
        "    port: 0\n"
        "    allow: [ 10.20.0.0/33, 10.20, fe80::1 ]\n"
        "    max_requests_per_s: 0\n"
        "    write: true\n");
    EXPECT_NE(text.find("3:"), std::string::npos) << text;
    EXPECT_NE(text.find("4:5: 'port' 0 is outside 1.."), std::string::npos) << text;
    EXPECT_NE(text.find("allow '10.20.0.0/33' is not an IPv4 subnet"), std::string::npos) << text;
    EXPECT_NE(text.find("allow '10.20' is not an IPv4 subnet"), std::string::npos) << text;
    EXPECT_NE(text.find("allow 'fe80::1' is not an IPv4 subnet"), std::string::npos) << text;
    EXPECT_NE(text.find("6:5: 'max_requests_per_s' 0 is outside 1.."), std::string::npos) << text;
    EXPECT_NE(text.find("unknown key 'write' in eip.commands (did you mean 'writes'?)"),
              std::string::npos)
        << text;
}

TEST(CommandsConfig, AllowMustBeAList) {
    EXPECT_NE(errors_of("eip: { commands: { allow: 10.0.0.0/8 } }\n")
                  .find("expected a list of subnets for 'allow'"),
              std::string::npos);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
