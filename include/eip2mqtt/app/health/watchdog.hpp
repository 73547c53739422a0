#pragma once
/// systemd's watchdog as a module of the gateway: pinged from the loop that does the work, at
/// half the unit's WatchdogSec, so that a wedged loop stops the pings and systemd restarts the
/// service. Nothing when systemd asked for no watchdog.
///
/// Threading: the loop only.

#include <boost/asio/any_io_executor.hpp>
#include <boost/asio/steady_timer.hpp>

#include "eip2mqtt/adapters/systemd/notifier.hpp"
#include "eip2mqtt/app/module.hpp"

namespace eip2mqtt::app {

class Watchdog final : public Module {
public:
    /// `notifier` outlives the watchdog.
    Watchdog(boost::asio::any_io_executor loop, adapters::systemd::Notifier& notifier)
        : notifier_(notifier), timer_(std::move(loop)) {}

    void start(core::MonoTime /*now*/) override { ping(); }
    void stop() override { timer_.cancel(); }

private:
    void ping();

    adapters::systemd::Notifier& notifier_;
    boost::asio::steady_timer timer_;
};

}  // namespace eip2mqtt::app
