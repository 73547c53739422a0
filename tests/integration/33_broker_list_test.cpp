// A list of brokers (`mqtt.url: [a, b]`): two independent Mosquittos, the first stopped, then
// restarted while the second stops. The tag tree follows the gateway from one to the other.

#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

constexpr std::uint32_t marker = 4711;

class BrokerListTest : public GatewayTest {
protected:
    void SetUp() override {
        standby_ = std::make_unique<Mosquitto>();
        GatewayOptions options;
        options.more_urls = {standby_->url()};
        start(ExchangeYaml::consume("line", "10.0.0.2", 7)
                  .length(4)
                  .timeout_ms(0)
                  .tag("MARKER", "0.0", "udint")
                  .str(),
              "", options);
    }
    void TearDown() override {
        GatewayTest::TearDown();
        standby_.reset();
    }

    /// What a subscriber to `url` made now must see: the gateway `online`, its tag MARKER,
    /// retained for a subscriber that comes later still, and `url` as the gateway's broker in
    /// its metrics. Mosquitto keeps no state across restarts here, and the two share none:
    /// everything comes from the gateway's connect to that broker.
    void expect_tree_on(const std::string& url, std::size_t connects) {
        MqttRecorder watcher(url, {topic("#")}, "watcher");
        ASSERT_TRUE(watcher.wait_for_message(
            availability_topic(), [](const std::string& p) { return p == "online"; }, 30s))
            << "the gateway never came online on " << url << "\n"
            << gateway_->output();
        const auto has_marker = [](const std::string& p) {
            return json::parse(p)["value"] == marker;
        };
        ASSERT_TRUE(watcher.wait_for_message(topic("line/MARKER"), has_marker, 15s))
            << "MARKER never arrived on " << url;
        MqttRecorder late(url, {topic("line/MARKER")}, "late");
        const auto retained = late.wait_for_message(topic("line/MARKER"), has_marker, 10s);
        ASSERT_TRUE(retained.has_value()) << "MARKER is not retained on " << url;
        EXPECT_TRUE(retained->retained);
        EXPECT_TRUE(watcher.wait_for_message(
            metrics_topic(), [&](const std::string& p) { return json::parse(p)["broker"] == url; },
            15s))
            << "the metrics never named " << url;
        EXPECT_TRUE(logged("MQTT connected to " + url + "\n", connects)) << gateway_->output();
    }

    /// Whether the gateway's output holds `text` `times` times, within a bounded wait (the
    /// output is a file its process writes on its own schedule).
    bool logged(const std::string& text, std::size_t times) const {
        for (int attempt = 0; attempt < 100; ++attempt) {
            const auto output = gateway_->output();
            std::size_t found = 0;
            for (auto at = output.find(text); at != std::string::npos;
                 at = output.find(text, at + 1)) {
                ++found;
            }
            if (found >= times) return true;
            std::this_thread::sleep_for(100ms);  // polling a file, bounded: 10 s in all
        }
        return false;
    }

    std::unique_ptr<Mosquitto> standby_;
};

TEST_F(BrokerListTest, TheTreeFollowsTheGatewayToTheNextBrokerAndBack) {
    send(DatagramBuilder("10.0.0.2", 7, 4)
             .set("0.0", TagType::udint, std::uint64_t{marker})
             .build());
    expect_tree_on(broker_->url(), 1);
    EXPECT_EQ(gateway_->output().find("MQTT connected to " + standby_->url() + "\n"),
              std::string::npos);

    // The first broker goes: the gateway moves to the second, which never saw it before.
    broker_->stop();
    expect_tree_on(standby_->url(), 1);

    // The first comes back, empty, and the second goes: the list wraps around to the first.
    broker_->start();
    standby_->stop();
    expect_tree_on(broker_->url(), 2);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
