#pragma once
// Shared by the foreground tools (sim, sniff): run a loop until SIGINT/SIGTERM, or until
// `duration_s` seconds passed when it is positive.

#include <boost/asio/io_context.hpp>

namespace eip2mqtt::app::detail {

void run_until_stopped(boost::asio::io_context& loop, double duration_s);

}  // namespace eip2mqtt::app::detail
