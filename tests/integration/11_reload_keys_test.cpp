// SIGHUP reloads, key by key (docs/operations.md, Reload): a change is applied
// whole (multicast groups left and joined on the running socket, publish settings without
// restarting an exchange or cancelling a write, a new metrics interval at once) or, when a key
// needs a restart, refused whole; the log names every changed key either way.

#include <signal.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <vector>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/igmp.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

/// A consumed exchange of 10.0.0.1 with one dint tag A at 0.0.
ExchangeYaml exchange(const std::string& name, std::uint32_t id) {
    return ExchangeYaml::consume(name, "10.0.0.1", id)
        .length(4)
        .period_ms(1000)
        .timeout_ms(0)
        .tag("A", "0.0", "dint");
}

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t rid, std::int64_t v) {
    return DatagramBuilder("10.0.0.1", exchange_id, 4)
        .request_id(rid)
        .set("0.0", TagType::dint, v)
        .build();
}

/// A produced exchange with one writable dint VALUE at 0.0, sent to 127.0.0.1:`port`.
std::string produced(const std::string& name, std::uint32_t id, std::uint16_t port,
                     std::uint32_t period_ms) {
    return ExchangeYaml::produce(name, "10.1.2.3", id, "127.0.0.1:" + std::to_string(port))
        .period_ms(period_ms)
        .tag("VALUE", "0.0", "dint", "writable: true")
        .str();
}

class ReloadKeysTest : public GatewayTest {
protected:
    /// Replaces the one occurrence of `from` in the configuration file by `to`.
    void replace_in_config(const std::string& from, const std::string& to) {
        std::ifstream in(config_path_);
        std::stringstream text;
        text << in.rdbuf();
        auto content = text.str();
        const auto at = content.find(from);
        ASSERT_NE(at, std::string::npos) << from << " not in\n" << content;
        content.replace(at, from.size(), to);
        std::ofstream(config_path_) << content;
    }
    /// Signals a reload and waits for its last line, `line`.
    void reload(const std::string& line) {
        gateway_->signal(SIGHUP);
        ASSERT_TRUE(gateway_->wait_for_output(line, 10s)) << gateway_->output();
    }
    /// Publishes `payload` to `exchange`'s VALUE as an MQTT 5 request answered on
    /// replies/reload with correlation data `id`.
    void write(const std::string& exchange, const std::string& payload, const std::string& id) {
        recorder_->publish_request(topic(exchange + "/VALUE/set"), payload, "replies/reload", id);
    }
    /// The correlation data of every result received so far.
    std::set<std::string> replied() const {
        std::set<std::string> ids;
        for (const auto& m : recorder_->messages_on("replies/reload")) {
            ids.insert(m.correlation_data);
        }
        return ids;
    }
};

TEST_F(ReloadKeysTest, AChangedMulticastGroupIsLeftAndTheNewOneJoined) {
    // The reload said "configuration applied" and kept the old group joined, the new one not.
    const auto old_group = test_multicast_group(1);
    const auto new_group = test_multicast_group(2);
    GatewayOptions options;
    options.eip_extra = "  multicast:\n    - { group: " + old_group + ", interface: lo }\n";
    start(exchange("kept", 1).str(), "", options);
    ASSERT_TRUE(igmp_joined("lo", old_group));
    ASSERT_FALSE(igmp_joined("lo", new_group));

    replace_in_config(old_group, new_group);
    reload("reload: applied eip.multicast\n");
    EXPECT_NE(gateway_->output().find("1 exchange(s) kept, 0 started, 0 stopped"),
              std::string::npos)
        << gateway_->output();
    // The gateway made both calls before it logged the line above.
    EXPECT_TRUE(igmp_joined("lo", new_group));
    EXPECT_FALSE(igmp_joined("lo", old_group));
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");
}

TEST_F(ReloadKeysTest, PublishSettingsApplyWithoutRestartingExchangesOrCancellingWrites) {
    // A new payload format restarted every exchange, answering queued writes "reloaded".
    UdpClient capture;
    start(exchange("kept", 1).str() + produced("sp", 10, capture.port(), 3600000),
          "  payload: json\n");
    ASSERT_TRUE(capture.receive(5s).has_value());
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");
    std::vector<std::string> ids;
    for (int i = 1; i <= 5; ++i) {
        ids.push_back("sp-" + std::to_string(i));
        write("sp", std::to_string(i), ids.back());
    }
    write("sp", "\"x\"", "sp-fence");  // answered at once, after the writes above are queued
    ASSERT_TRUE(recorder_->wait_for([](const std::vector<Received>& all) {
        return std::any_of(all.begin(), all.end(), [](const Received& m) {
            return m.topic == "replies/reload" && m.correlation_data == "sp-fence";
        });
    }));

    replace_in_config("  payload: json\n", "  payload: raw\n");
    reload("reload: applied mqtt.payload\n");
    EXPECT_NE(gateway_->output().find("2 exchange(s) kept, 0 started, 0 stopped"),
              std::string::npos)
        << gateway_->output();
    // The retained state is published again in the new form, without a new datagram.
    EXPECT_TRUE(recorder_->wait_for_message(topic("kept/A"),
                                            [](const std::string& p) { return p == "11"; }));
    // The queued writes are still queued: no result, none cancelled.
    const auto from = recorder_->count();
    EXPECT_TRUE(recorder_->wait_for_message(
        metrics_topic(),
        [](const std::string& p) { return json::parse(p)["writes_cancelled"] == 0; }, 10s, from));
    const auto answered = replied();
    for (const auto& id : ids) EXPECT_FALSE(answered.contains(id)) << id;
}

TEST_F(ReloadKeysTest, AChangeThatNeedsARestartIsRefusedWholeAndNamed) {
    start(exchange("kept", 1).str(), "  keepalive_s: 30\n");
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");

    replace_in_config("  keepalive_s: 30\n", "  keepalive_s: 60\n");
    replace_in_config("{ name: A,", "{ name: B,");
    reload(
        "reload refused: mqtt.keepalive_s needs a restart (systemctl restart eip2mqtt); nothing is "
        "applied (also changed: exchanges[kept].tags[B] (added), exchanges[kept].tags[A] "
        "(removed)); the running configuration is kept");
    // Nor the exchange's change: the old tag still takes the datagrams.
    send(datagram(1, 2, 12));
    expect_field(topic("kept/A"), "value", "12");
    EXPECT_EQ(gateway_->output().find("configuration applied"), std::string::npos)
        << gateway_->output();
}

TEST_F(ReloadKeysTest, ANewMetricsIntervalAppliesAtOnce) {
    // The wait under way, for the old interval, went on: an hour's interval made shorter
    // still waited the hour.
    start(exchange("kept", 1).str());
    replace_in_config("  metrics_interval_s: 1\n", "  metrics_interval_s: 3600\n");
    reload("reload: applied mqtt.metrics_interval_s\n");
    replace_in_config("  metrics_interval_s: 3600\n", "  metrics_interval_s: 2\n");
    replace_in_config("  log_level: debug\n", "  log_level: info\n");
    reload("reload: applied gateway.log_level, mqtt.metrics_interval_s\n");
    const auto from = recorder_->count();
    EXPECT_TRUE(recorder_->wait_for_message(
        metrics_topic(), [](const std::string&) { return true; }, 10s, from));
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
