#include "app/cli/detail/network_load_report.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>
#include <string>

#include "eip2mqtt/core/plan/network_load.hpp"

namespace eip2mqtt::app::detail {
namespace {

/// `value` with at most `decimals` decimals, trailing zeros dropped: 100, 333.333, 0.5.
std::string figure(double value, int decimals) {
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", decimals, value);
    std::string s = text;
    if (s.find('.') != std::string::npos) {
        while (s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
    }
    return s;
}

std::string share_text(double share) { return figure(share * 100, 2) + " %"; }

}  // namespace

std::string rate(double datagrams_per_s, double bits_per_s) {
    return figure(datagrams_per_s, 3) + " datagrams/s, " + figure(std::round(bits_per_s), 0) +
           " bit/s";
}

bool report_network_load(const std::vector<core::plan::ExchangePlan>& plans, double link_mbps,
                         std::ostream& out, std::ostream& err) {
    const auto load = core::plan::network_load(plans);
    if (load.exchanges.empty()) return true;
    const double share = load.link_share(link_mbps);
    const auto link = "eip.link_mbps " + figure(link_mbps, 3);
    out << "\nnetwork load of the " << load.exchanges.size() << " produced exchange"
        << (load.exchanges.size() == 1 ? "" : "s") << ": "
        << rate(load.datagrams_per_s, load.bits_per_s) << " on the wire, " << share_text(share)
        << " of " << link << "\n"
        << "  each datagram counted as its data plus " << core::plan::wire_overhead_bytes
        << " bytes: Ethernet preamble and start delimiter 8, header 14, frame check 4, "
           "inter-frame gap 12; IPv4 20; UDP 8; EIP header 32\n";
    for (const auto& to : load.destinations) {
        out << "  to " << to.destination << ": " << to.exchanges << " exchange"
            << (to.exchanges == 1 ? "" : "s") << ", " << rate(to.datagrams_per_s, to.bits_per_s)
            << "\n";
    }
    for (const auto& exchange : load.exchanges) {
        out << "  " << exchange.name << ": " << rate(exchange.datagrams_per_s, exchange.bits_per_s)
            << ", first sent " << figure(static_cast<double>(exchange.phase.count()) / 1e6, 6)
            << " ms after start\n";
    }
    if (share > 1) {
        err << "error: the produced exchanges need " << share_text(share) << " of " << link
            << ": more than the link carries; lengthen periods, shorten exchanges, or set "
               "eip.link_mbps to the link's real speed\n";
        return false;
    }
    if (share > link_share_warning) {
        out << "  warning: the produced exchanges take " << share_text(share) << " of " << link
            << ", over half of the link: other traffic and bursts may delay or lose datagrams\n";
    }
    return true;
}

}  // namespace eip2mqtt::app::detail
