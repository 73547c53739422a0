#include "eip2mqtt/adapters/udp/port_holders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <system_error>

#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::adapters::udp {
namespace {

namespace fs = std::filesystem;

/// The inodes of the sockets bound to `port` in one /proc/net/udp-style table. Each row:
/// `sl local_address rem_address st tx:rx tr:when retrnsmt uid timeout inode ...`, the local
/// address as hex `ADDRESS:PORT`.
void collect_inodes(const char* table, std::uint16_t port, std::set<unsigned long>& inodes) {
    std::ifstream in(table);
    std::string line;
    std::getline(in, line);  // the column headings
    while (std::getline(in, line)) {
        std::istringstream row(line);
        std::string slot, local, remote, state, queues, timer, retransmits, uid, timeout;
        unsigned long inode = 0;
        if (!(row >> slot >> local >> remote >> state >> queues >> timer >> retransmits >> uid >>
              timeout >> inode)) {
            continue;
        }
        const auto colon = local.rfind(':');
        if (colon == std::string::npos) continue;
        unsigned long local_port = 0;
        try {
            local_port = std::stoul(local.substr(colon + 1), nullptr, 16);
        } catch (const std::exception&) {
            continue;
        }
        if (local_port == port && inode != 0) inodes.insert(inode);
    }
}

std::string command_line(const fs::path& process) {
    std::ifstream in(process / "cmdline", std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    while (!text.empty() && text.back() == '\0') text.pop_back();
    std::replace(text.begin(), text.end(), '\0', ' ');
    return core::printable(text);
}

/// Whether one of the process's descriptors is a socket of `inodes`.
bool holds_one_of(const fs::path& process, const std::set<unsigned long>& inodes) {
    std::error_code ec;
    for (fs::directory_iterator fd(process / "fd", ec), end; !ec && fd != end; fd.increment(ec)) {
        std::error_code link_error;
        const auto target = fs::read_symlink(fd->path(), link_error).string();
        unsigned long inode = 0;
        if (!link_error && std::sscanf(target.c_str(), "socket:[%lu]", &inode) == 1 &&
            inodes.count(inode) != 0) {
            return true;
        }
    }
    return false;
}

}  // namespace

PortHolders udp_port_holders(std::uint16_t port) {
    std::set<unsigned long> inodes;
    collect_inodes("/proc/net/udp", port, inodes);
    collect_inodes("/proc/net/udp6", port, inodes);
    PortHolders holders;
    holders.sockets = inodes.size();
    if (inodes.empty()) return holders;
    std::error_code ec;
    for (fs::directory_iterator entry("/proc", ec), end; !ec && entry != end; entry.increment(ec)) {
        const auto name = entry->path().filename().string();
        if (name.empty() || !std::all_of(name.begin(), name.end(),
                                         [](unsigned char c) { return std::isdigit(c) != 0; }))
            continue;
        if (holds_one_of(entry->path(), inodes)) {
            holders.processes.push_back({std::stoi(name), command_line(entry->path())});
        }
    }
    std::sort(holders.processes.begin(), holders.processes.end(),
              [](const PortHolder& a, const PortHolder& b) { return a.pid < b.pid; });
    return holders;
}

std::string describe_udp_port_holders(std::uint16_t port) {
    const auto holders = udp_port_holders(port);
    if (holders.sockets == 0) return {};
    if (holders.processes.empty()) {
        return fmt::format(
            "held by a process this user cannot see (`sudo ss -ulpn 'sport = :{}'` "
            "names it)",
            port);
    }
    std::string text;
    for (const auto& holder : holders.processes) {
        text += text.empty() ? "held by " : ", ";
        text += fmt::format("process {} ({})", holder.pid, holder.command);
    }
    return text;
}

}  // namespace eip2mqtt::adapters::udp
