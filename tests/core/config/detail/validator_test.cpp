// validate(): the run (file order) and the gateway and mqtt sections.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "eip2mqtt/core/config/config.hpp"
#include "tests/core/config/config_builders.hpp"

namespace eip2mqtt::core::config {
namespace EIP2MQTT_THIS_FILE {

TEST(Validate, ValidConfigHasNoDiagnostics) { EXPECT_TRUE(validate(valid()).empty()); }

TEST(Validate, ControlCharactersAndInvalidUtf8InBaseTopicGatewayIdAndClientId) {
    auto c = valid();
    c.mqtt.base_topic = std::string("acme\0", 5);
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("base_topic").line);
    EXPECT_TRUE(mentions(d, "contains a NUL character")) << d.message;

    c = valid();
    c.gateway.id = "gw\x1B";
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.gateway.marks.of("id").line);
    EXPECT_EQ(d.message, "gateway id 'gw\\x1B' contains a control character (it is a topic level)");

    c = valid();
    c.mqtt.client_id = "client\xFF";
    c.mqtt.marks.add("client_id", at(next_line++, 3));
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("client_id").line);
    EXPECT_EQ(d.message, "client_id 'client\\xFF' is not valid UTF-8");
    c.mqtt.client_id = std::string(65536, 'c');
    EXPECT_EQ(only(validate(c)).message, "client_id is 65536 bytes long (MQTT allows 65535)");
    c.mqtt.client_id = std::string(65535, 'c');
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, GatewayTopicsTooLongAreRefusedAtTheIdOrOnceAtTheBaseTopic) {
    // acme/site/_gateway/{id}/metrics: 27 bytes and the id.
    auto c = valid();
    c.gateway.id = std::string(65535 - 27, 'g');
    EXPECT_TRUE(validate(c).empty());
    c.gateway.id += 'g';
    auto d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.gateway.marks.of("id").line);
    EXPECT_TRUE(mentions(d, "topic '{base_topic}/_gateway/{gateway.id}/metrics' 65536 bytes long"))
        << d.message;
    // A base_topic leaving no room for any id: said once, not for each exchange and tag.
    c = valid();
    c.mqtt.base_topic = std::string(65535 - 18, 'b');
    d = only(validate(c));
    EXPECT_EQ(d.mark.line, c.mqtt.marks.of("base_topic").line);
    EXPECT_TRUE(mentions(d,
                         "(65517 bytes) makes topic '{base_topic}/_gateway/{gateway.id}/metrics' "
                         "65537 bytes long"))  // with the id `gw`
        << d.message;
}

TEST(Validate, MqttSection) {
    auto c = valid();
    c.mqtt.qos = 3;
    EXPECT_EQ(only(validate(c)).mark.line, c.mqtt.marks.of("qos").line);
    c = valid();
    c.mqtt.version = 4;
    EXPECT_EQ(only(validate(c)).mark.line, c.mqtt.marks.of("version").line);
    c.mqtt.version = 3;
    EXPECT_TRUE(validate(c).empty());
}

TEST(Validate, GatewaySection) {
    auto c = valid();
    c.gateway.id.clear();
    EXPECT_EQ(only(validate(c)).mark.line, c.gateway.marks.of("id").line);
    c = valid();
    c.gateway.log_level = "verbose";
    EXPECT_EQ(only(validate(c)).mark.line, c.gateway.marks.of("log_level").line);
}

TEST(Validate, DiagnosticsComeInFileOrder) {
    auto c = valid();
    c.exchanges[1].tags[0].spec.mutable_extras().min = 5;  // later line
    c.exchanges[1].tags[0].spec.mutable_extras().max = 1;
    c.exchanges[0].spec.period = 0ms;  // earlier line
    c.gateway.id.clear();              // earliest line
    auto found = validate(c);
    ASSERT_EQ(found.size(), 3u);
    EXPECT_TRUE(std::is_sorted(found.begin(), found.end(), [](const auto& a, const auto& b) {
        return a.mark.line < b.mark.line;
    }));
    // Rows of other files (point lists) follow the configuration file's own.
    c.exchanges[0].tags.push_back(tag("PL", 16, 0, TagType::byte));  // past the end
    c.exchanges[0].tags.back().marks = {};
    c.exchanges[0].tags.back().marks.node = {"a.csv", 2, 1};
    found = validate(c);
    ASSERT_EQ(found.size(), 4u);
    EXPECT_EQ(found.back().mark.file, "a.csv");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::core::config
