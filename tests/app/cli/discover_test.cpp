// `eip2mqtt discover`: a host that does not resolve and a node that never answers, each said
// as such with its exit code. (Answering nodes: tests/integration, against the real binary.)

#include <gtest/gtest.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <sstream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "tests/support/free_port.hpp"

namespace eip2mqtt::app {
namespace EIP2MQTT_THIS_FILE {

/// run_discover sets up the process's "eip2mqtt" logger: each test gets a fresh one and gives
/// the earlier default logger back after.
class DiscoverTest : public testing::Test {
protected:
    DiscoverTest() { spdlog::drop("eip2mqtt"); }
    ~DiscoverTest() override {
        spdlog::drop("eip2mqtt");
        spdlog::set_default_logger(previous_);
        spdlog::set_level(level_);
    }
    int discover(const DiscoverOptions& options) { return run_discover(options, out_, err_); }

    std::shared_ptr<spdlog::logger> previous_ = spdlog::default_logger();
    spdlog::level::level_enum level_ = spdlog::get_level();
    std::ostringstream out_;
    std::ostringstream err_;
};

TEST_F(DiscoverTest, AHostThatDoesNotResolveIsExit2) {
    DiscoverOptions options;
    options.hosts = {"127.0.0.1", "no-such-host.invalid"};
    EXPECT_EQ(discover(options), 2);
    EXPECT_EQ(err_.str(), "eip2mqtt discover: cannot resolve no-such-host.invalid\n");
    EXPECT_TRUE(out_.str().empty());
}

TEST_F(DiscoverTest, ANodeThatNeverAnswersIsSaidSoAndIsExit1) {
    const auto port = test::free_udp_port();
    DiscoverOptions options;
    options.hosts = {"127.0.0.1:" + std::to_string(port)};
    options.timeout_ms = 50;
    options.attempts = 2;
    EXPECT_EQ(discover(options), 1);
    EXPECT_EQ(out_.str(),
              "127.0.0.1:" + std::to_string(port) + ": no answer after 2 attempts of 50 ms\n");
    EXPECT_TRUE(err_.str().empty());
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app
