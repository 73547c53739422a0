#pragma once
/// Who holds a local UDP port: the processes with a socket bound to it, read from /proc, so that
/// a refused bind can name the program in the way instead of only saying "in use".

#include <cstdint>
#include <string>
#include <vector>

namespace eip2mqtt::adapters::udp {

struct PortHolder {
    int pid = 0;
    std::string command;  ///< its command line, printable (core::printable), words joined by spaces
};

/// The processes with an IPv4 or IPv6 UDP socket bound to local `port`, in pid order, each once.
/// A process whose descriptors this user may not read is missing: `sockets` still counts its
/// socket. Reads /proc/net/udp{,6} and /proc/<pid>/fd: for start-up messages, not the data path.
struct PortHolders {
    std::size_t sockets = 0;  ///< sockets bound to the port, seen or not
    std::vector<PortHolder> processes;
};
PortHolders udp_port_holders(std::uint16_t port);

/// One clause naming the holders for an error message: "held by process 1234 (eip2mqtt run -c
/// x.yaml)", "held by a process this user cannot see (`sudo ss -ulpn 'sport = :N'` names it)",
/// or empty when no socket holds the port (any more).
std::string describe_udp_port_holders(std::uint16_t port);

}  // namespace eip2mqtt::adapters::udp
