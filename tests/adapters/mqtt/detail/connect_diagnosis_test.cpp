// ConnectDiagnosis: what a failed attempt or a lost connection is logged as, timed on the
// client's clock (a fake here, so that a connection's lifetime is exact).

#include "adapters/mqtt/detail/connect_diagnosis.hpp"

#include <gtest/gtest.h>

#include "tests/support/fakes/fake_clock.hpp"

namespace eip2mqtt::adapters::mqtt::detail {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

constexpr auto kNoDisconnect = "no reason given (no DISCONNECT from the broker)";

struct ConnectDiagnosisTest : ::testing::Test {
    ConnectDiagnosisTest() {
        options.client_id = "gw-1";
        options.clock = &clock;
    }
    test::FakeClock clock;
    ClientOptions options;
};

TEST_F(ConnectDiagnosisTest, SilentShortLivedLossesInARowNameTheSharedClientId) {
    ConnectDiagnosis diagnosis(options);
    for (std::size_t i = 1; i < SilentLossPattern::kLossesInARow; ++i) {
        diagnosis.on_connected();
        clock.advance(2s);
        EXPECT_EQ(diagnosis.explain_loss("", true), kNoDisconnect);
    }
    diagnosis.on_connected();
    clock.advance(2s);
    EXPECT_EQ(diagnosis.explain_loss("", true),
              "no reason given: " + SilentLossPattern::explain("gw-1"));
}

TEST_F(ConnectDiagnosisTest, ALongLivedConnectionIsMeasuredFromItsConnectOnTheClock) {
    ConnectDiagnosis diagnosis(options);
    for (std::size_t i = 0; i < SilentLossPattern::kLossesInARow + 1; ++i) {
        diagnosis.on_connected();
        clock.advance(SilentLossPattern::kShortLived + 1s);
        EXPECT_EQ(diagnosis.explain_loss("", true), kNoDisconnect) << i;
    }
}

TEST_F(ConnectDiagnosisTest, ALossWithACauseKeepsIt) {
    ConnectDiagnosis diagnosis(options);
    diagnosis.on_connected();
    EXPECT_EQ(diagnosis.explain_loss("broker sent DISCONNECT", false), "broker sent DISCONNECT");
}

TEST_F(ConnectDiagnosisTest, FailedAttemptsAreLoggedOncePerIntervalOfTheClock) {
    ConnectDiagnosis diagnosis(options);
    EXPECT_EQ(diagnosis.record_connect_failure(), 1u);
    clock.advance(10s);
    EXPECT_EQ(diagnosis.record_connect_failure(), 0u);
    clock.advance(core::ThrottledLog::default_interval);
    EXPECT_EQ(diagnosis.record_connect_failure(), 2u);
    diagnosis.on_connected();
    EXPECT_EQ(diagnosis.record_connect_failure(), 1u) << "a connect starts the log afresh";
}

TEST_F(ConnectDiagnosisTest, AnMqtt5RefusalIsExplained) {
    options.version = 5;
    ConnectDiagnosis diagnosis(options);
    const auto reason = diagnosis.explain_connect_failure("refused", kUnsupportedProtocolVersion,
                                                          nullptr, std::nullopt);
    EXPECT_EQ(reason, "refused: " + *mqtt5_refusal(kUnsupportedProtocolVersion, "refused", false));
}

TEST_F(ConnectDiagnosisTest, ASpecificReasonOfAnMqtt311ClientIsKept) {
    options.version = 3;
    ConnectDiagnosis diagnosis(options);
    EXPECT_EQ(
        diagnosis.explain_connect_failure("Bad user name or password", 4, nullptr, std::nullopt),
        "Bad user name or password");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::mqtt::detail
