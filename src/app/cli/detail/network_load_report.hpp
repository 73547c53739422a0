#pragma once
/// `check`'s account of the network load of the produced exchanges (core::plan::network_load).

#include <iosfwd>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::app::detail {

/// Load warns past this share of eip.link_mbps, and is refused past the whole link.
inline constexpr double link_share_warning = 0.5;

/// `20 datagrams/s, 16640 bit/s`: as `check` and `sniff` print a load.
std::string rate(double datagrams_per_s, double bits_per_s);

/// Prints, when `plans` produce anything, the total load on the wire, the load per destination,
/// and each exchange's rate, load and phase, with a warning past half of `link_mbps`. Past the
/// whole link, says so on `err` and returns false: `check` then refuses the configuration.
bool report_network_load(const std::vector<core::plan::ExchangePlan>& plans, double link_mbps,
                         std::ostream& out, std::ostream& err);

}  // namespace eip2mqtt::app::detail
