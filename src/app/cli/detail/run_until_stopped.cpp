#include "app/cli/detail/run_until_stopped.hpp"

#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <csignal>

namespace eip2mqtt::app::detail {

void run_until_stopped(boost::asio::io_context& loop, double duration_s) {
    boost::asio::signal_set signals(loop, SIGINT, SIGTERM);
    signals.async_wait([&](const boost::system::error_code& error, int) {
        if (!error) loop.stop();
    });
    boost::asio::steady_timer duration_timer(loop);
    if (duration_s > 0) {
        duration_timer.expires_after(std::chrono::duration_cast<std::chrono::nanoseconds>(
            std::chrono::duration<double>(duration_s)));
        duration_timer.async_wait([&](const boost::system::error_code& error) {
            if (!error) loop.stop();
        });
    }
    loop.run();
}

}  // namespace eip2mqtt::app::detail
