#pragma once
/// The passive capture behind `sniff`: which frames it asks the kernel for, and what it tells an
/// operator who lacks the privilege to capture.

#include <boost/asio/any_io_executor.hpp>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>

#include "eip2mqtt/adapters/capture/packet_capture.hpp"
#include "eip2mqtt/app/cli/commands.hpp"

namespace eip2mqtt::app::detail {

/// The pcap filter for IPv4 UDP datagrams to `port`, and to `address` when not empty (an IPv4
/// address, checked by the caller).
std::string capture_filter(std::uint16_t port, const std::string& address);

/// What sniff prints when it may not capture: why, and the two ways to get the privilege, with
/// the path of this binary in the setcap command.
std::string capture_privilege_help(const std::string& interface, const std::string& reason);

/// Opens the capture for `options` on `port`. When it cannot (no privilege, no such interface,
/// a bad --bind), says why on `err` and returns nullptr: sniff never falls back to binding the
/// port, which would take datagrams from the gateway.
std::unique_ptr<adapters::capture::PacketCapture> open_capture(
    boost::asio::any_io_executor executor, const SniffOptions& options, std::uint16_t port,
    std::ostream& err);

}  // namespace eip2mqtt::app::detail
