#include "eip2mqtt/adapters/yaml/discovered_skeleton.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

namespace command = core::command;
namespace wire = core::wire;

using command::ExchangeMode;

wire::ExchangeKey key(std::uint32_t producer, std::uint32_t exchange) {
    return {wire::ProducerId{producer}, exchange};
}

DiscoveredExchange told(wire::ExchangeKey k, ExchangeMode mode, std::uint16_t length,
                        std::uint32_t period_ms) {
    command::ExchangeConfig config;
    config.key = k;
    config.mode = mode;
    config.length = length;
    config.period_ms = period_ms;
    config.destination_type = command::DestinationType::multicast;
    config.destination = 0xE0000701;
    return {{k, mode}, config, {}};
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(DiscoveredSkeleton, ProducedExchangesGetAnItemWithWhatTheNodeTold) {
    DiscoveredNode node;
    node.address = "10.20.0.7:7937";
    node.total = 1;
    node.exchanges.push_back(told(key(0x0A000009, 3), ExchangeMode::produced, 40, 20));
    node.exchanges[0].config->signature = 0x0102;
    const auto text = discovered_skeleton(std::vector{node});
    EXPECT_TRUE(has(text, "exchanges:\n  - name: \"10.0.0.9-3\"\n    direction: consume\n"));
    EXPECT_TRUE(has(text, "    length: 40  # data bytes, as the node told\n"));
    EXPECT_TRUE(has(text, "    signature: \"1.2\"\n"));
    EXPECT_TRUE(has(text, "    period_ms: 20  # as the node told\n"));
    // Without dots: RabbitMQ would turn each into a level (docs/brokers.md).
    EXPECT_TRUE(has(text, "    topic: \"10-0-0-9/3\"  # under base_topic\n"));
    EXPECT_TRUE(has(text, "multicast group 224.0.7.1 (the gateway joins it with eip.multicast"));
    EXPECT_TRUE(has(text, "# told by 10.20.0.7:7937: state idle"));
}

TEST(DiscoveredSkeleton, WhatGetsNoItemIsSaidInComments) {
    DiscoveredNode silent;
    silent.address = "10.20.0.8:7937";
    silent.problem = "no answer after 3 attempts of 500 ms";
    DiscoveredNode node;
    node.address = "10.20.0.7:7937";
    node.total = 4;
    node.exchanges.push_back(told(key(0x0A000005, 7), ExchangeMode::consumed, 8, 100));
    node.exchanges.push_back({{key(0x0A000009, 5)}, std::nullopt, "status unknown_exchange"});
    node.exchanges.push_back(told(key(0x0A000009, 6), ExchangeMode::produced, 0, 0));
    const auto text = discovered_skeleton(std::vector{silent, node});
    EXPECT_TRUE(has(text, "# 10.20.0.8:7937: no answer after 3 attempts of 500 ms\n"));
    EXPECT_TRUE(has(text, "# 10.0.0.5/7: consumed by 10.20.0.7:7937 (8 bytes every 100 ms)"));
    EXPECT_FALSE(has(text, "name: \"10.0.0.5-7\""));
    EXPECT_TRUE(has(text, "# 10.0.0.9/5 (10.20.0.7:7937): not retrieved: status unknown_exchange"));
    EXPECT_TRUE(has(text, "# 10.20.0.7:7937: 1 of its 4 exchanges could not be listed"));
    // Values the configuration refuses become valid ones with a TODO.
    EXPECT_TRUE(has(text, "    length: 1  # TODO: the node told 0 bytes"));
    EXPECT_TRUE(has(text, "    period_ms: 1000  # TODO: the node told 0"));
}

TEST(DiscoveredSkeleton, AKeyListedTwiceGetsOneItem) {
    DiscoveredNode a;
    a.address = "a";
    a.exchanges.push_back(told(key(0x0A000009, 3), ExchangeMode::produced, 4, 20));
    auto b = a;
    b.address = "b";
    const auto text = discovered_skeleton(std::vector{a, b});
    EXPECT_EQ(text.find("name: \"10.0.0.9-3\""), text.rfind("name: \"10.0.0.9-3\""));
    EXPECT_TRUE(has(text, "# discover --yaml: 1 exchange the nodes produce"));
}

TEST(DiscoveredSkeleton, NothingProducedIsNoList) {
    const auto text = discovered_skeleton(std::vector<DiscoveredNode>{});
    EXPECT_TRUE(has(text, "0 exchanges"));
    EXPECT_FALSE(has(text, "exchanges:\n"));
}

TEST(DiscoveredSkeleton, WhatANodeToldCannotLeaveItsCommentLine) {
    // A NAK's text, as a hostile node sends it: a newline, then configuration.
    const std::string nak =
        "NAK x\neip: {commands: {enabled: true, writes: true, allow: [0.0.0.0/0]}}\r\x1b[2J";
    DiscoveredNode node;
    node.address = "10.20.0.7:7937";
    node.problem = nak;
    DiscoveredNode other;
    other.address = "10.20.0.8:7937";
    other.total = 1;
    other.exchanges.push_back({{key(0x0A000009, 5)}, std::nullopt, nak});
    const auto text = discovered_skeleton(std::vector{node, other});
    EXPECT_FALSE(has(text, "\neip:")) << text;
    EXPECT_FALSE(has(text, "\r")) << text;
    EXPECT_FALSE(has(text, "\x1b")) << text;
    EXPECT_TRUE(has(text, "# 10.20.0.7:7937: NAK x\\x0aeip: {commands:")) << text;
    // Every line is a comment: nothing the node told became a key.
    std::size_t start = 0;
    while (start < text.size()) {
        const auto end = text.find('\n', start);
        EXPECT_EQ(text[start], '#') << text.substr(start, end - start);
        start = end == std::string::npos ? text.size() : end + 1;
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
