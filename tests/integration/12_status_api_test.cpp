// The status API on the metrics listener: /api/status and /api/exchanges/{name} from a running
// gateway, as their schemas say, read-only, and what they say moving with the datagrams and a
// reload.

#include <signal.h>

#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/http_get.hpp"
#include "tests/support/schema_check.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using json = nlohmann::json;
using namespace std::chrono_literals;

class StatusApiTest : public GatewayTest {
protected:
    void SetUp() override {
        port_ = free_tcp_port();
        GatewayOptions options;
        // Sparkplug on, so that its session is on the page too.
        options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port_) +
                           "\nsparkplug:\n  group_id: plant1\n";
        start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
                      .length(8)
                      .tag("SPEED", "0.0", "dint", "unit: rpm")
                      .tag("FLOW", "4.0", "real")
                      .str() +
                  ExchangeYaml::setpoint_command(),
              "", options);
    }

    /// GET `path`: its code and its body parsed (null when it is no JSON).
    std::pair<std::string, json> get(const std::string& path) {
        const auto [code, body] = status_and_body(http_get(port_, path));
        bodies_.push_back(body);
        return {code, json::parse(body, nullptr, false)};
    }

    std::uint16_t port_ = 0;
    std::vector<std::string> bodies_;
};

TEST_F(StatusApiTest, ShowTheGatewayEachExchangeAndItsTagsAsTheirSchemasSay) {
    for (std::uint16_t rid = 1; rid <= 3; ++rid) {
        send(DatagramBuilder("10.0.0.2", 7, 8)
                 .request_id(rid * 2)
                 .set("0.0", TagType::dint, std::int64_t{rid * 100})
                 .set("4.0", TagType::real, 2.5)
                 .build());
    }
    expect_field(topic("pump/SPEED"), "value", "300");

    const auto [code, status] = get("/api/status");
    ASSERT_EQ(code, "200") << bodies_.back();
    EXPECT_EQ(status["gateway"]["id"], "test-gw");
    EXPECT_EQ(status["gateway"]["config"]["file"], config_path_);
    EXPECT_EQ(status["gateway"]["config"]["reloads"], 0);
    EXPECT_EQ(status["gateway"]["mqtt"]["connected"], true);
    ASSERT_EQ(status["gateway"]["mqtt"]["brokers"].size(), 1u) << bodies_.back();
    EXPECT_EQ(status["gateway"]["mqtt"]["brokers"][0]["connected"], true);
    EXPECT_EQ(status["gateway"]["sparkplug"]["group_id"], "plant1");
    EXPECT_EQ(status["gateway"]["sparkplug"]["devices"], 2);  // one per exchange
    ASSERT_EQ(status["exchanges"].size(), 2u) << bodies_.back();
    const auto& pump = status["exchanges"][0];
    EXPECT_EQ(pump["name"], "pump");
    EXPECT_EQ(pump["direction"], "consume");
    EXPECT_EQ(pump["status"]["state"], "ok");
    EXPECT_EQ(pump["status"]["accepted"], 3);
    EXPECT_EQ(pump["status"]["missed"], 2);
    EXPECT_EQ(status["exchanges"][1]["name"], "cmd");
    EXPECT_EQ(status["exchanges"][1]["direction"], "produce");

    const auto [pump_code, one] = get("/api/exchanges/pump");
    ASSERT_EQ(pump_code, "200") << bodies_.back();
    ASSERT_EQ(one["tags"].size(), 2u) << bodies_.back();
    EXPECT_EQ(one["tags"][0]["name"], "SPEED");
    EXPECT_EQ(one["tags"][0]["unit"], "rpm");
    EXPECT_EQ(one["tags"][0]["topic"], topic("pump/SPEED"));
    EXPECT_EQ(one["tags"][0]["sample"]["value"], 300);
    EXPECT_EQ(one["tags"][0]["sample"]["quality"], "good");
    EXPECT_EQ(one["tags"][1]["sample"]["value"], 2.5);
    const auto [cmd_code, produced] = get("/api/exchanges/cmd");
    ASSERT_EQ(cmd_code, "200") << bodies_.back();
    EXPECT_EQ(produced["tags"][0]["sample"]["value"], 42);

    const auto problems = schema_problems({{schema_file("api-status.json"), bodies_[0]},
                                           {schema_file("api-exchange.json"), bodies_[1]},
                                           {schema_file("api-exchange.json"), bodies_[2]}});
    for (std::size_t i = 0; i < problems.size(); ++i) {
        EXPECT_EQ(problems[i], "") << bodies_[i];
    }
}

TEST_F(StatusApiTest, IsReadOnlyAndSaysWhatItDoesNotKnow) {
    EXPECT_EQ(get("/api/exchanges/nothing").first, "404");
    EXPECT_EQ(get("/api/nothing").first, "404");
    for (const auto* method : {"POST", "PUT", "DELETE", "PATCH"}) {
        const auto response = http_request(port_, method, "/api/exchanges/cmd");
        EXPECT_EQ(status_and_body(response).first, "405") << method << ": " << response;
    }
    // Before any datagram: waiting, no sample, no age.
    const auto [code, pump] = get("/api/exchanges/pump");
    ASSERT_EQ(code, "200");
    EXPECT_EQ(pump["status"]["state"], "waiting");
    EXPECT_TRUE(pump["last_seen_age_ms"].is_null());
    EXPECT_TRUE(pump["tags"][0]["sample"].is_null());
    EXPECT_EQ(schema_problem(schema_file("api-exchange.json"), bodies_.back()), "");
    // The produced image is what it was: nothing asked changed it.
    EXPECT_EQ(get("/api/exchanges/cmd").second["tags"][0]["sample"]["value"], 42);
}

TEST_F(StatusApiTest, SaysWhenTheConfigurationWasReloaded) {
    const auto before = get("/api/status").second["gateway"]["config"]["loaded_at"];
    gateway_->signal(SIGHUP);
    // The reload is applied on the loop: read until it shows (bounded).
    json config = json::object();
    for (int i = 0; i < 400 && config.value("reloads", 0) == 0; ++i) {
        std::this_thread::sleep_for(50ms);
        config = get("/api/status").second["gateway"]["config"];
    }
    EXPECT_EQ(config["reloads"], 1);
    EXPECT_GE(config["loaded_at"].get<std::int64_t>(), before.get<std::int64_t>());
}

/// The `data:` of the first event named `name` in an event stream's text, parsed (null: none).
json event_data(const std::string& stream, const std::string& name) {
    const auto at = stream.find("event: " + name + "\ndata: ");
    if (at == std::string::npos) return json();
    const auto from = at + name.size() + 14;
    return json::parse(stream.substr(from, stream.find('\n', from) - from), nullptr, false);
}

TEST_F(StatusApiTest, ThePageAndItsEventStreamFollowTheDatagramsLive) {
    const auto page = http_get(port_, "/");
    EXPECT_EQ(status_and_body(page).first, "200");
    EXPECT_NE(page.find("Content-Type: text/html"), std::string::npos) << page;
    EXPECT_NE(page.find(R"(src="/status.js")"), std::string::npos) << page;
    EXPECT_EQ(status_and_body(http_get(port_, "/status.js")).first, "200");

    send(DatagramBuilder("10.0.0.2", 7, 8).request_id(1).set("0.0", TagType::dint, 100).build());
    expect_field(topic("pump/SPEED"), "value", "100");
    const auto stream =
        http_read_until(port_, "/api/events?open=pump,nothing", "event: exchange", 10000);
    EXPECT_NE(stream.find("Content-Type: text/event-stream"), std::string::npos) << stream;
    const auto status = event_data(stream, "status");
    const auto pump = event_data(stream, "exchange");
    ASSERT_TRUE(pump.is_object()) << stream;
    EXPECT_EQ(pump["tags"][0]["sample"]["value"], 100);
    EXPECT_EQ(schema_problem(schema_file("api-status.json"), status.dump()), "");
    EXPECT_EQ(schema_problem(schema_file("api-exchange.json"), pump.dump()), "");

    // A new value reaches an open stream; then the exchange, silent, turns stale in it.
    send(DatagramBuilder("10.0.0.2", 7, 8).request_id(2).set("0.0", TagType::dint, 200).build());
    EXPECT_NE(http_read_until(port_, "/api/events?open=pump", R"("value":200)", 10000)
                  .find(R"("value":200)"),
              std::string::npos);
    EXPECT_NE(http_read_until(port_, "/api/events", R"("state":"stale")", 20000)
                  .find(R"("state":"stale")"),
              std::string::npos);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
