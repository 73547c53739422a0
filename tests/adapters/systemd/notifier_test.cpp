#include "eip2mqtt/adapters/systemd/notifier.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

namespace eip2mqtt::adapters::systemd {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;

/// Sets the variables systemd passes for the test's scope, and removes them after.
class SystemdEnvironment {
public:
    SystemdEnvironment(const char* socket, const char* watchdog_usec) {
        set("NOTIFY_SOCKET", socket);
        set("WATCHDOG_USEC", watchdog_usec);
        ::unsetenv("WATCHDOG_PID");
    }
    ~SystemdEnvironment() {
        ::unsetenv("NOTIFY_SOCKET");
        ::unsetenv("WATCHDOG_USEC");
    }

private:
    static void set(const char* name, const char* value) {
        if (value != nullptr) {
            ::setenv(name, value, 1);
        } else {
            ::unsetenv(name);
        }
    }
};

// The watchdog is pinged at half of WatchdogSec, so one late ping never gets the service
// killed (that it is pinged at all is tested against the real binary in 09_systemd_test).
TEST(Notifier, PingsTheWatchdogAtHalfOfWatchdogSec) {
    SystemdEnvironment env("/run/test-notify", "400000");
    Notifier notifier;
    EXPECT_TRUE(notifier.enabled());
    EXPECT_EQ(notifier.watchdog_interval(), std::optional<std::chrono::microseconds>(200ms));
}

TEST(Notifier, NoWatchdogWithoutWatchdogSecAndNothingWithoutASocket) {
    {
        SystemdEnvironment env("/run/test-notify", nullptr);
        Notifier notifier;
        EXPECT_TRUE(notifier.enabled());
        EXPECT_FALSE(notifier.watchdog_interval().has_value());
    }
    {
        SystemdEnvironment env(nullptr, "400000");
        Notifier notifier;
        EXPECT_FALSE(notifier.enabled());
        EXPECT_FALSE(notifier.watchdog_interval().has_value());
    }
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::systemd
