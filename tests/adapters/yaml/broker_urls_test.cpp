// `mqtt.url`: one broker as a string, or a list of them tried in turn.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/adapters/yaml/loading.hpp"

namespace eip2mqtt::adapters::yaml {
namespace EIP2MQTT_THIS_FILE {

using Urls = std::vector<std::string>;

TEST(BrokerUrls, AStringIsAListOfOne) {
    const auto config = good("mqtt:\n  url: tcp://broker-a:1883\n" + minimal_exchange);
    EXPECT_EQ(config.mqtt.urls, Urls{"tcp://broker-a:1883"});
}

TEST(BrokerUrls, AListKeepsItsOrder) {
    const auto config = good(
        "mqtt:\n  url: [ \"tcp://broker-b:1883\", \"tcp://broker-a:1883\" ]\n" + minimal_exchange);
    EXPECT_EQ(config.mqtt.urls, (Urls{"tcp://broker-b:1883", "tcp://broker-a:1883"}));
}

TEST(BrokerUrls, ABlockListReadsAsAFlowList) {
    const auto config = good(
        "mqtt:\n"
        "  url:\n"
        "    - ssl://node1.cluster:8883\n"
        "    - ssl://node2.cluster:8883\n"
        "    - ssl://node3.cluster:8883\n" +
        minimal_exchange);
    EXPECT_EQ(config.mqtt.urls, (Urls{"ssl://node1.cluster:8883", "ssl://node2.cluster:8883",
                                      "ssl://node3.cluster:8883"}));
}

TEST(BrokerUrls, WithoutTheKeyTheLocalBroker) {
    EXPECT_EQ(good(minimal_exchange).mqtt.urls, Urls{"tcp://localhost:1883"});
}

TEST(BrokerUrls, AnEmptyListIsRefusedAtTheKey) {
    const auto text = dump(bad("mqtt:\n  url: []\n" + minimal_exchange));
    EXPECT_NE(text.find("test.yaml:2:3: mqtt url is an empty list"), std::string::npos) << text;
}

TEST(BrokerUrls, AnEmptyStringIsRefusedAsAlways) {
    const auto text = dump(bad("mqtt:\n  url: \"\"\n" + minimal_exchange));
    EXPECT_NE(text.find("test.yaml:2:3: mqtt url is empty"), std::string::npos) << text;
}

TEST(BrokerUrls, AnEmptyEntryIsRefusedAtItsLineAndColumn) {
    const auto text =
        dump(bad("mqtt:\n"
                 "  url:\n"
                 "    - tcp://a:1883\n"
                 "    - \"\"\n" +
                 minimal_exchange));
    EXPECT_NE(text.find("test.yaml:4:7: mqtt url is empty"), std::string::npos) << text;
}

TEST(BrokerUrls, AnEntryThatIsNoStringIsRefusedAtItsLineAndColumn) {
    const auto text = dump(bad("mqtt:\n  url: [ tcp://a:1883, { host: b } ]\n" + minimal_exchange));
    EXPECT_NE(text.find("test.yaml:2:24: expected a string for 'url'"), std::string::npos) << text;
}

TEST(BrokerUrls, AnEntryOfAnotherSchemeIsRefusedAtItsLineAndColumn) {
    const auto text =
        dump(bad("mqtt:\n"
                 "  url:\n"
                 "    - ssl://a:8883\n"
                 "    - ssl://b:8883\n"
                 "    - tcp://c:1883\n" +
                 minimal_exchange));
    EXPECT_NE(text.find("test.yaml:5:7: mqtt url 'tcp://c:1883' does not use the scheme of "
                        "'ssl://a:8883'"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("test.yaml:4:"), std::string::npos) << text;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::yaml
