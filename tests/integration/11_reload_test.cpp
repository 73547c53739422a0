// SIGHUP reloads: a valid change is applied without dropping the MQTT session or unchanged
// exchanges; an invalid file is refused and the old configuration keeps running. With a YAML
// syntax cache, an unchanged file is loaded from it and an edited one parsed.

#include <signal.h>
#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

using core::plan::TagType;
using nlohmann::json;
using namespace std::chrono_literals;

std::string exchange(const std::string& name, std::uint32_t id, const std::string& tags) {
    return "  - name: " + name + "\n    direction: consume\n    producer_id: 10.0.0.1\n" +
           "    exchange_id: " + std::to_string(id) + "\n    length: 4\n    period_ms: 1000\n" +
           "    timeout_ms: 0\n    topic: " + name + "\n    tags:\n" + tags;
}

const std::string tag_a = "      - { name: A, address: \"0.0\", type: dint }\n";
const std::string tag_b = "      - { name: B, address: \"0.0\", type: int }\n";

std::vector<std::byte> datagram(std::uint32_t exchange_id, std::uint16_t rid, std::int64_t v) {
    return DatagramBuilder("10.0.0.1", exchange_id, 4)
        .request_id(rid)
        .set("0.0", TagType::dint, v)
        .build();
}

class ReloadTest : public GatewayTest {
protected:
    /// Rewrites the configuration file with other exchanges, keeping the rest.
    void rewrite_exchanges(const std::string& exchanges_yaml) {
        std::ifstream in(config_path_);
        std::stringstream text;
        text << in.rdbuf();
        auto content = text.str();
        content = content.substr(0, content.find("exchanges:\n")) + "exchanges:\n" + exchanges_yaml;
        std::ofstream(config_path_) << content;
    }
    std::size_t onlines() const {
        std::size_t n = 0;
        for (const auto& m : recorder_->messages_on(availability_topic()))
            n += m.payload == "online";
        return n;
    }
};

TEST_F(ReloadTest, ValidChangeIsAppliedWithoutDroppingTheSessionOrUnchangedExchanges) {
    start(exchange("kept", 1, tag_a) + exchange("removed", 2, tag_a) +
          exchange("changed", 3, tag_a));
    send(datagram(1, 1, 11));
    send(datagram(2, 1, 22));
    send(datagram(3, 1, 33));
    expect_field(topic("kept/A"), "value", "11");
    expect_field(topic("removed/A"), "value", "22");
    expect_field(topic("changed/A"), "value", "33");
    const auto onlines_before = onlines();

    rewrite_exchanges(exchange("kept", 1, tag_a) + exchange("changed", 3, tag_b) +
                      exchange("added", 4, tag_a));
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("1 exchange(s) kept, 2 started, 2 stopped"),
              std::string::npos)
        << gateway_->output();

    // The removed exchange's retained topics are cleared (an empty retained message).
    EXPECT_TRUE(recorder_->wait_for_message(topic("removed/A"),
                                            [](const std::string& p) { return p.empty(); }));
    EXPECT_TRUE(recorder_->wait_for_message(topic("changed/A"),
                                            [](const std::string& p) { return p.empty(); }));
    // The added and the changed exchange consume; the kept one never stopped (its sequence
    // goes on from request id 1: a restarted exchange would resynchronise and count nothing).
    send(datagram(4, 1, 44));
    expect_field(topic("added/A"), "value", "44");
    send(datagram(3, 5, 55));
    expect_field(topic("changed/B"), "value", "55");
    send(datagram(1, 3, 12));
    expect_field(topic("kept/A"), "value", "12");
    const auto status = recorder_->wait_for_message(
        topic("kept/_status"), [](const std::string& p) { return json::parse(p)["missed"] == 1; });
    EXPECT_TRUE(status.has_value()) << "kept exchange lost its sequence state";
    // Datagrams of the removed exchange are now unknown.
    send(datagram(2, 2, 23));
    EXPECT_TRUE(recorder_->wait_for_message(metrics_topic(), [](const std::string& p) {
        return json::parse(p)["dropped"]["unknown_exchange"] == 1;
    }));
    // The MQTT session was kept: no second `online`.
    EXPECT_EQ(onlines(), onlines_before);
}

TEST_F(ReloadTest, InvalidFileIsRefusedAndTheOldConfigurationKeepsRunning) {
    start(exchange("kept", 1, tag_a));
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");

    rewrite_exchanges(exchange("kept", 1, tag_a) + "    colour: blue\n");
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("reload refused", 10s)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("colour"), std::string::npos) << gateway_->output();
    send(datagram(1, 2, 12));
    expect_field(topic("kept/A"), "value", "12");
    EXPECT_TRUE(gateway_->running());
}

TEST_F(ReloadTest, APointListThatIsADirectoryOrAFifoIsRefusedAndTheOldConfigurationKeepsRunning) {
    // A directory made the reload die of std::bad_alloc (exit 1); a FIFO blocked the loop.
    start(exchange("kept", 1, tag_a));
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");

    const auto directory = dir_.path() + "/dir.csv";
    std::filesystem::create_directory(directory);
    rewrite_exchanges(exchange("kept", 1, tag_a) + "    points: " + directory + "\n");
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output(
        "point list '" + directory + "' is not a regular file (a directory)", 10s))
        << gateway_->output();
    send(datagram(1, 2, 12));
    expect_field(topic("kept/A"), "value", "12");

    const auto fifo = dir_.path() + "/fifo.csv";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    rewrite_exchanges(exchange("kept", 1, tag_a) + "    points: " + fifo + "\n");
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(
        gateway_->wait_for_output("point list '" + fifo + "' is not a regular file (a FIFO)", 10s))
        << gateway_->output();
    send(datagram(1, 3, 13));
    expect_field(topic("kept/A"), "value", "13");

    EXPECT_TRUE(gateway_->running());
    const auto output = gateway_->output();
    std::size_t refusals = 0;
    for (auto at = output.find("reload refused"); at != std::string::npos;
         at = output.find("reload refused", at + 1)) {
        ++refusals;
    }
    EXPECT_EQ(refusals, 2u) << output;
}

TEST_F(ReloadTest, TheSyntaxCacheServesAnUnchangedFileAndNeverAnEditedOne) {
    TempDir cache;
    GatewayOptions options;
    options.env["CACHE_DIRECTORY"] = cache.path();  // as systemd's CacheDirectory= sets it
    start(exchange("kept", 1, tag_a), "", options);
    const std::string hit = "unchanged since its YAML syntax was cached";
    EXPECT_EQ(gateway_->output().find(hit), std::string::npos) << gateway_->output();
    send(datagram(1, 1, 11));
    expect_field(topic("kept/A"), "value", "11");

    // A restart loads the tree the first start saved, and runs the same.
    gateway_->signal(SIGTERM);
    ASSERT_TRUE(gateway_->wait(10s).has_value());
    start_gateway();
    EXPECT_NE(gateway_->output().find(hit), std::string::npos) << gateway_->output();
    send(datagram(1, 2, 12));
    expect_field(topic("kept/A"), "value", "12");

    // An edited file is parsed again on reload, and its change applied.
    rewrite_exchanges(exchange("kept", 1, tag_b) + exchange("added", 4, tag_a));
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("configuration applied", 10s)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("is not used (the configuration changed)"), std::string::npos)
        << gateway_->output();
    send(datagram(4, 1, 44));
    expect_field(topic("added/A"), "value", "44");
    send(datagram(1, 5, 55));
    expect_field(topic("kept/B"), "value", "55");
}

}  // namespace
}  // namespace eip2mqtt::test
