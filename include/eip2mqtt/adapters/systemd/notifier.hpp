#pragma once
/// systemd's notification protocol (sd_notify): READY, RELOADING, STOPPING, WATCHDOG and STATUS.
/// Every call is a no-op when the process was not started with NOTIFY_SOCKET.

#include <chrono>
#include <optional>
#include <string>

namespace eip2mqtt::adapters::systemd {

class Notifier {
public:
    Notifier();

    bool enabled() const { return enabled_; }
    void ready(const std::string& status);
    void reloading();
    void stopping();
    void watchdog();
    void status(const std::string& status);
    /// The interval at which watchdog() must be called (half of WatchdogSec), if systemd asked.
    std::optional<std::chrono::microseconds> watchdog_interval() const { return watchdog_; }

private:
    bool enabled_ = false;
    std::optional<std::chrono::microseconds> watchdog_;
};

}  // namespace eip2mqtt::adapters::systemd
