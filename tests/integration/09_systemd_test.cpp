// systemd integration: notifications on a NOTIFY_SOCKET of the test's own, the unit file
// accepted by systemd-analyze, and what `cmake --install` puts where.

#include <signal.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/notify_socket.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

const std::string one_exchange = ExchangeYaml::consume("pump", "10.0.0.2", 7)
                                     .length(4)
                                     .period_ms(1000)
                                     .tag("SPEED", "0.0", "real")
                                     .str();

class SystemdTest : public GatewayTest {};

TEST_F(SystemdTest, ReadyWatchdogReloadingAndStoppingAreNotified) {
    NotifySocket notify(dir_.path() + "/notify");
    // WatchdogSec=400ms: the daemon pings every 200 ms.
    gateway_env_ = {{"NOTIFY_SOCKET", notify.path()}, {"WATCHDOG_USEC", "400000"}};
    start(one_exchange);
    // READY came before `online`, so it is already waiting in the socket.
    ASSERT_TRUE(notify.wait_for("READY=1", 5s).has_value());

    // The watchdog keeps being pinged (at half of WatchdogSec: Notifier's unit test; how
    // late a ping may come on a busy machine is not something a test can assert).
    for (int pings = 0; pings < 6; ++pings) {
        ASSERT_TRUE(notify.wait_for("WATCHDOG=1", 5s).has_value()) << "after " << pings << " pings";
    }

    gateway_->signal(SIGHUP);
    EXPECT_TRUE(notify.wait_for("RELOADING=1", 5s).has_value());
    EXPECT_TRUE(notify.wait_for("READY=1", 5s).has_value());

    gateway_->signal(SIGTERM);
    EXPECT_TRUE(notify.wait_for("STOPPING=1", 5s).has_value());
    EXPECT_EQ(gateway_->wait(10s), 0);
}

TEST(SystemdUnit, SystemdAnalyzeVerifyAcceptsTheUnit) {
    TempDir dir;
    // The unit names the installed binary; point it at the one under test.
    std::ifstream in(std::string(EIP2MQTT_SOURCE_DIR) + "/systemd/eip2mqtt.service");
    std::stringstream unit;
    unit << in.rdbuf();
    std::string text = unit.str();
    for (std::size_t at; (at = text.find("/usr/local/bin/eip2mqtt")) != std::string::npos;) {
        text.replace(at, std::string("/usr/local/bin/eip2mqtt").size(), gateway_binary());
    }
    for (const auto* key :
         {"Type=notify", "WatchdogSec=", "ExecReload=", "Restart=on-failure",
          "StateDirectory=", "ProtectSystem=strict", "PrivateTmp=yes", "NoNewPrivileges=yes",
          "CapabilityBoundingSet=\n", "RestrictAddressFamilies="}) {
        EXPECT_NE(text.find(key), std::string::npos) << key;
    }
    const auto path = dir.write("eip2mqtt.service", text);
    // Documentation=man:eip2mqtt(1) names a page this machine need not have installed; the
    // package's test checks that it resolves (50_package_test.cpp).
    const auto result = run_command({"/usr/bin/systemd-analyze", "verify", "--man=no", path}, 60s);
    EXPECT_EQ(result.status, 0) << result.output;
}

TEST(Install, CmakeInstallPutsBinaryUnitAndExampleConfig) {
    TempDir dir;
    const std::string build_dir = std::filesystem::path(gateway_binary()).parent_path();
    const auto result = run_command(
        {"/usr/bin/cmake", "--install", build_dir, "--prefix", dir.path() + "/usr"}, 60s);
    ASSERT_EQ(result.status, 0) << result.output;
    std::vector<std::string> installed;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir.path())) {
        installed.push_back(entry.path().string().substr(dir.path().size()));
    }
    auto has = [&](const std::string& suffix) {
        return std::any_of(installed.begin(), installed.end(),
                           [&](const std::string& p) { return p.ends_with(suffix); });
    };
    EXPECT_TRUE(has("/bin/eip2mqtt"));
    EXPECT_TRUE(has("/eip2mqtt/eip2mqtt.yaml"));
    EXPECT_TRUE(has("/systemd/system/eip2mqtt.service"));
    EXPECT_TRUE(has("/doc/eip2mqtt/README.md"));
    EXPECT_TRUE(has("/doc/eip2mqtt/docs/protocol.md"));
    EXPECT_TRUE(has("/doc/eip2mqtt/docs/mqtt-api.md"));
    EXPECT_TRUE(has("/doc/eip2mqtt/docs/schema/tag-value.json"));
    EXPECT_TRUE(has("/man/man1/eip2mqtt.1"));
}

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// As dpkg does with a conffile: an edited configuration is kept, the new example put beside it.
TEST(Install, CmakeInstallKeepsAnEditedConfiguration) {
    TempDir dir;
    const std::string build_dir = std::filesystem::path(gateway_binary()).parent_path();
    const std::vector<std::string> install{"/usr/bin/cmake", "--install", build_dir, "--prefix",
                                           dir.path() + "/usr"};
    ASSERT_EQ(run_command(install, 60s).status, 0);
    const auto config = dir.path() + "/usr/etc/eip2mqtt/eip2mqtt.yaml";
    const auto example =
        read_text(std::string(EIP2MQTT_SOURCE_DIR) + "/etc/eip2mqtt/eip2mqtt.yaml");
    ASSERT_EQ(read_text(config), example);

    // Installed again over an unedited file: nothing to keep, no .new.
    ASSERT_EQ(run_command(install, 60s).status, 0);
    EXPECT_FALSE(std::filesystem::exists(config + ".new"));

    const std::string edited = "# edited for the plant\n" + example;
    std::ofstream(config) << edited;
    const auto result = run_command(install, 60s);
    ASSERT_EQ(result.status, 0) << result.output;
    EXPECT_EQ(read_text(config), edited);
    EXPECT_EQ(read_text(config + ".new"), example);
    EXPECT_NE(result.output.find("Kept: " + config), std::string::npos) << result.output;
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
