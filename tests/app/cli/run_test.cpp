// `run` up to the gateway: the log level asked for on the command line wins over the
// configuration's, which applies otherwise; a configuration with errors is refused, its errors
// logged, and the gateway never built. (The gateway running is the integration tests'.)

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <string>

#include "app/cli/detail/run_config.hpp"
#include "tests/app/support/logger_restore.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

class RunTest : public ::testing::Test {
protected:
    /// load_run_config of a configuration whose gateway.log_level is warn.
    std::optional<core::config::Config> load(std::string log_level, const std::string& yaml) {
        test::LoggerRestore::fresh();  // each run sets up its own logger
        RunOptions options;
        options.config_path = dir_.write("gw.yaml", yaml);
        options.log_level = std::move(log_level);
        return load_run_config(options);
    }

    test::LoggerRestore logger_;
    test::TempDir dir_;
    const std::string warn_yaml =
        "gateway:\n  log_level: warn\nmqtt:\n  url: tcp://a:1883\nexchanges:\n"
        "  - { name: ex, producer_id: 10.0.0.1, exchange_id: 1, length: 8 }\n";
};

TEST_F(RunTest, TheConfigurationsLogLevelAppliesWhenNoneIsAsked) {
    const auto config = load("", warn_yaml);
    ASSERT_TRUE(config.has_value());
    EXPECT_EQ(config->exchanges.size(), 1u);
    EXPECT_EQ(spdlog::get_level(), spdlog::level::warn);
}

TEST_F(RunTest, TheLogLevelAskedForWinsOverTheConfigurations) {
    ASSERT_TRUE(load("debug", warn_yaml).has_value());
    EXPECT_EQ(spdlog::get_level(), spdlog::level::debug);
}

TEST_F(RunTest, AConfigurationWithErrorsIsRefusedAndTheGatewayNeverBuilt) {
    EXPECT_FALSE(load("", "mqtt:\n  url: tcp://a:1883\nexchanges: 3\n").has_value());
    test::LoggerRestore::fresh();
    RunOptions options;
    options.config_path = dir_.path() + "/missing.yaml";
    EXPECT_EQ(run_gateway(options), 1);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
