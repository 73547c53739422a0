#include "eip2mqtt/app/health/watchdog.hpp"

namespace eip2mqtt::app {

void Watchdog::ping() {
    const auto interval = notifier_.watchdog_interval();
    if (!interval) return;
    notifier_.watchdog();
    timer_.expires_after(*interval);
    timer_.async_wait([this](const boost::system::error_code& error) {
        if (!error) ping();
    });
}

}  // namespace eip2mqtt::app
