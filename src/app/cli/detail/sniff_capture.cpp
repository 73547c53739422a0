#include "app/cli/detail/sniff_capture.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <ostream>
#include <system_error>

#include "eip2mqtt/adapters/udp/endpoint.hpp"

namespace eip2mqtt::app::detail {

std::string capture_filter(std::uint16_t port, const std::string& address) {
    // Datagrams *to* the port: received by this host, or sent by it (a gateway's productions).
    std::string filter = fmt::format("ip and udp dst port {}", port);
    if (!address.empty()) filter += " and dst host " + address;
    return filter;
}

std::string capture_privilege_help(const std::string& interface, const std::string& reason) {
    std::error_code ec;
    auto binary = std::filesystem::read_symlink("/proc/self/exe", ec).string();
    if (ec || binary.empty()) binary = "$(command -v eip2mqtt)";
    return fmt::format(
        "eip2mqtt sniff: capturing on '{}' needs the CAP_NET_RAW capability, which this "
        "process lacks ({}).\n"
        "sniff watches the traffic passively, beside the gateway, and never binds the port. To "
        "let it capture, either run it as root:\n"
        "  sudo eip2mqtt sniff ...\n"
        "or give the binary the capability once (then any user may sniff):\n"
        "  sudo setcap cap_net_raw,cap_net_admin+eip {}\n",
        interface, reason, binary);
}

std::unique_ptr<adapters::capture::PacketCapture> open_capture(
    boost::asio::any_io_executor executor, const SniffOptions& options, std::uint16_t port,
    std::ostream& err) {
    if (!options.bind.empty() && !adapters::udp::parse_ipv4(options.bind)) {
        err << "eip2mqtt sniff: --bind '" << options.bind << "' is not an IPv4 address\n";
        return nullptr;
    }
    adapters::capture::CaptureOptions capture;
    capture.interface = options.interface;
    capture.filter = capture_filter(port, options.bind);
    try {
        return std::make_unique<adapters::capture::PacketCapture>(std::move(executor), capture);
    } catch (const adapters::capture::CaptureError& e) {
        if (e.permission_denied()) {
            err << capture_privilege_help(options.interface, e.what());
        } else {
            err << "eip2mqtt sniff: " << e.what() << '\n';
        }
        return nullptr;
    }
}

}  // namespace eip2mqtt::app::detail
