// SIGHUP with a large file: it is parsed and checked off the loop, so a produced exchange goes on
// sending and /healthz on answering while it parses; a large file that is refused leaves the
// running configuration as it was, and a stop during the parse ends the gateway cleanly.
//
// Each test prints the longest gap between two produced datagrams during its reload: before
// the parse left the loop, the gap covered the whole parse (and no datagram arrived within it).

#include <signal.h>

#include <optional>

#include "tests/integration/reload_large_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using core::plan::TagType;
using Clock = ReloadClock;

TEST_F(ReloadLargeTest, ProductionGoesOnWhileAFileOf100000TagsIsParsed) {
    start_producing();
    rewrite_exchanges(produced(capture_.port()) + kept() + plant(1000));
    HealthPoller health(metrics_port_);
    EXPECT_GT(reload_and_count("configuration applied"), 0u) << gateway_->output();
    health.stop();
    EXPECT_TRUE(health.failures().empty()) << health.failures().front();
    EXPECT_NE(gateway_->output().find("2 exchange(s) kept, 1000 started, 0 stopped"),
              std::string::npos)
        << gateway_->output();
    // The new exchanges run.
    send(DatagramBuilder("10.0.0.2", 1099, 400)
             .set("396.0", TagType::dint, std::int64_t{7})
             .build());
    expect_field(topic("c999/T99"), "value", "7");
}

TEST_F(ReloadLargeTest, ALargeFileThatIsRefusedLeavesProductionHealthAndTheRunningConfiguration) {
    // WatchdogSec=1s: the loop pings every 500 ms, STATUS= comes every metrics interval (1 s).
    NotifyRecorder systemd(dir_.path() + "/notify");
    gateway_env_ = {{"NOTIFY_SOCKET", systemd.path()}, {"WATCHDOG_USEC", "1000000"}};
    start_producing();
    // 6,000 exchanges of 100 tags (32 MB): the loop used to stop for its parse, 9 to 26 s on
    // the CI machine, about as long as /healthz waits for the loop (10 s) or longer.
    rewrite_exchanges(produced(capture_.port()) + kept() + plant(6000, true));
    HealthPoller health(metrics_port_);
    EXPECT_GT(reload_and_count("reload refused"), 0u) << gateway_->output();
    health.stop();
    // Between RELOADING=1 and READY=1 (one ordered stream: no timing involved), the watchdog
    // was pinged and the status kept current; before, the loop sent nothing in between.
    const auto deadline = Clock::now() + 10s;
    while (!systemd.during_reload("WATCHDOG=1") && Clock::now() < deadline) {
        std::this_thread::sleep_for(20ms);
    }
    EXPECT_GT(systemd.during_reload("WATCHDOG=1").value_or(0), 0u);
    EXPECT_GT(systemd.during_reload("STATUS=").value_or(0), 0u);
    EXPECT_GT(health.polls(), 0u);
    EXPECT_TRUE(health.failures().empty()) << health.failures().front();
    EXPECT_NE(gateway_->output().find("colour"), std::string::npos) << gateway_->output();
    // The running configuration goes on: `kept` consumes, no `c0` was started.
    send(DatagramBuilder("10.0.0.1", 1, 4)
             .request_id(1)
             .set("0.0", TagType::dint, std::int64_t{11})
             .build());
    expect_field(topic("kept/A"), "value", "11");
    EXPECT_EQ(gateway_->output().find("configuration applied"), std::string::npos);
    EXPECT_TRUE(gateway_->running());
}

TEST_F(ReloadLargeTest, AStopWhileAFileIsParsedEndsTheGatewayCleanly) {
    start_producing();
    rewrite_exchanges(produced(capture_.port()) + kept() + plant(6000, true));
    gateway_->signal(SIGHUP);
    ASSERT_TRUE(gateway_->wait_for_output("SIGHUP: reloading", 10s)) << gateway_->output();
    gateway_->signal(SIGTERM);
    // The parse is given up: the gateway stops without finishing it (which would log the
    // file's refusal first) and exits 0 (no crash, nothing left behind a sanitizer reports).
    EXPECT_EQ(gateway_->wait(60s), std::optional<int>(0)) << gateway_->output();
    EXPECT_NE(gateway_->output().find("stopped:"), std::string::npos) << gateway_->output();
    EXPECT_EQ(gateway_->output().find("reload refused"), std::string::npos) << gateway_->output();
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
