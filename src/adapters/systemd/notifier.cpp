#include "eip2mqtt/adapters/systemd/notifier.hpp"

#include <systemd/sd-daemon.h>

#include <cstdlib>

namespace eip2mqtt::adapters::systemd {

Notifier::Notifier() {
    const char* socket = std::getenv("NOTIFY_SOCKET");
    enabled_ = socket != nullptr && *socket != '\0';
    std::uint64_t usec = 0;
    if (enabled_ && sd_watchdog_enabled(0, &usec) > 0 && usec > 0) {
        watchdog_ = std::chrono::microseconds(usec / 2);
    }
}

void Notifier::ready(const std::string& status) {
    if (enabled_) sd_notifyf(0, "READY=1\nSTATUS=%s", status.c_str());
}

void Notifier::reloading() {
    if (enabled_) sd_notify(0, "RELOADING=1");
}

void Notifier::stopping() {
    if (enabled_) sd_notify(0, "STOPPING=1");
}

void Notifier::watchdog() {
    if (enabled_) sd_notify(0, "WATCHDOG=1");
}

void Notifier::status(const std::string& status) {
    if (enabled_) sd_notifyf(0, "STATUS=%s", status.c_str());
}

}  // namespace eip2mqtt::adapters::systemd
