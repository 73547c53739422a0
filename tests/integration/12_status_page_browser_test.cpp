// The status page in a real browser: Debian's chromium, driven by puppeteer-core
// (tests/support/browser/status_page.js), on a gateway fed datagrams. The page shows every
// exchange, a tag's value changes on screen while datagrams come, the write log shows an MQTT
// write and its result, the exchange turns stale once they stop and the log's warning of it is
// listed, and the console has no error. The screenshot is kept in the build tree
// (test-artifacts/status-page.png). How long the change took is printed, never judged. And the list
// of 105 exchanges (status_list.js): paged 100 at a time, searched, sorted by a column.

#include <atomic>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/support/child_process.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using json = nlohmann::json;
using namespace std::chrono_literals;

/// The last line of the driver's output that is its `step`, parsed (null: none).
json step(const std::string& output, const std::string& name) {
    const auto at = output.rfind(R"({"step":")" + name + "\"");
    if (at == std::string::npos) return json();
    return json::parse(output.substr(at, output.find('\n', at) - at), nullptr, false);
}

/// Whether one of the warnings the page listed (the driver's `warnings` step) holds `text`.
bool listed_warning(const std::string& output, const std::string& text) {
    const auto warnings = step(output, "warnings");
    for (const auto& line : warnings["lines"]) {
        if (line.get<std::string>().find(text) != std::string::npos) return true;
    }
    return false;
}

class StatusPageBrowserTest : public GatewayTest {};

TEST_F(StatusPageBrowserTest,
       ShowsEveryExchangeFollowsTheValuesLogsAWriteAndTurnsStaleWithNoConsoleError) {
    const auto port = free_tcp_port();
    GatewayOptions options;
    options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port) + "\n";
    start(
        ExchangeYaml::consume("pump", "10.0.0.2", 7).length(4).tag("SPEED", "0.0", "dint").str() +
            ExchangeYaml::consume("fan", "10.0.0.3", 8).length(4).tag("RPM", "0.0", "dint").str() +
            ExchangeYaml::setpoint_command(),
        "", options);
    // Datagrams every 100 ms with a new SPEED each, until the page saw one change (bounded).
    std::atomic<bool> sending{true};
    std::thread sender([&] {
        for (std::uint16_t rid = 1; rid <= 600 && sending; ++rid) {
            send(DatagramBuilder("10.0.0.2", 7, 4)
                     .request_id(rid)
                     .set("0.0", TagType::dint, std::int64_t{1000 + rid})
                     .build());
            std::this_thread::sleep_for(100ms);
        }
    });
    const auto artifacts = std::filesystem::path(EIP2MQTT_TEST_ARTIFACTS);
    std::filesystem::create_directories(artifacts);
    const auto screenshot = (artifacts / "status-page.png").string();
    std::filesystem::remove(screenshot);
    ChildProcess browser({EIP2MQTT_NODE, EIP2MQTT_BROWSER_SCRIPT, EIP2MQTT_CHROMIUM,
                          "http://127.0.0.1:" + std::to_string(port) + "/", "pump", "SPEED", "3",
                          screenshot, "SETPOINT=7"});
    const bool changed = browser.wait_for_output(R"({"step":"changed")", 120s);
    sending = false;
    sender.join();
    ASSERT_TRUE(changed) << browser.output();
    EXPECT_EQ(write_result("cmd/SETPOINT/set", "7"), R"({"ok":true})");
    ASSERT_TRUE(browser.wait_for_output(R"({"step":"done")", 120s)) << browser.output();
    EXPECT_EQ(browser.wait(30s), 0) << browser.output();

    const auto output = browser.output();
    // Sorted by name, the page's first order.
    EXPECT_EQ(step(output, "shown")["exchanges"], json::array({"cmd", "fan", "pump"})) << output;
    const auto write = step(output, "write");
    EXPECT_EQ(write["origin"], "mqtt") << output;
    EXPECT_EQ(write["target"], topic("cmd/SETPOINT/set")) << output;
    EXPECT_EQ(write["result"], "ok") << output;
    const auto change = step(output, "changed");
    EXPECT_NE(change["first"], change["second"]) << output;
    std::cout << "status page: SPEED changed on screen " << change["ms"]
              << " ms after it was first read\n";
    // SPEED's sparkline is drawn from its values so far.
    EXPECT_EQ(step(output, "sparkline")["drawn"], 1) << output;
    // The state, and why: no datagram for some seconds, beyond the exchange's timeout.
    const std::string stale = step(output, "stale")["state"];
    EXPECT_EQ(stale.rfind("stale: no datagram for ", 0), 0u) << output;
    EXPECT_NE(stale.find(" s (timeout 3 s)"), std::string::npos) << output;
    // The log's warning that it went stale is among the last warnings the page lists.
    EXPECT_TRUE(listed_warning(output, "exchange pump is stale")) << output;
    EXPECT_EQ(step(output, "done")["errors"], json::array()) << output;
    EXPECT_TRUE(std::filesystem::exists(screenshot));
}

TEST_F(StatusPageBrowserTest, ListsExchangesAHundredToAPageSearchedAndSortedByAColumn) {
    const auto port = free_tcp_port();
    GatewayOptions options;
    options.sections = "metrics:\n  listen: 127.0.0.1:" + std::to_string(port) + "\n";
    std::string exchanges;
    for (std::uint32_t n = 0; n < 105; ++n) {
        const auto digits = std::to_string(1000 + n).substr(1);  // x000 to x104
        exchanges += ExchangeYaml::consume("x" + digits, "10.0.0.2", n + 1)
                         .length(4)
                         .tag("V", "0.0", "dint")
                         .str();
    }
    start(exchanges, "", options);
    ChildProcess browser({EIP2MQTT_NODE, EIP2MQTT_BROWSER_LIST_SCRIPT, EIP2MQTT_CHROMIUM,
                          "http://127.0.0.1:" + std::to_string(port) + "/", "5"});
    ASSERT_EQ(browser.wait(120s), 0) << browser.output();
    const auto output = browser.output();
    const auto seen = json::parse(output.substr(output.rfind("{\"count\"")), nullptr, false);
    ASSERT_TRUE(seen.is_object()) << output;
    EXPECT_EQ(seen["count"], "105 exchange(s)") << output;
    ASSERT_EQ(seen["first_page"].size(), 100u) << output;
    EXPECT_EQ(seen["first_page"][0], "x000") << output;
    EXPECT_EQ(seen["first_page"][99], "x099") << output;
    EXPECT_EQ(seen["next_page"], json::array({"x100", "x101", "x102", "x103", "x104"})) << output;
    // The names with a 5: x005, x015 ... x095 and x050 to x059, back on the first page.
    ASSERT_EQ(seen["searched"].size(), 19u) << output;
    EXPECT_EQ(seen["searched"][0], "x005") << output;
    EXPECT_EQ(seen["searched"][18], "x095") << output;
    // Sorted by name already: a click on its column sorts the other way.
    EXPECT_EQ(seen["sorted_first"], "x095") << output;
    EXPECT_EQ(seen["errors"], json::array()) << output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
