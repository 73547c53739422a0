#pragma once
/// Multicast group membership (IP_ADD_MEMBERSHIP) on a UDP socket, and a socket that only joins:
/// it makes the interface accept a group's traffic for a passive capture without taking any of it.

#include <string>
#include <vector>

namespace eip2mqtt::adapters::udp {

struct MulticastMembership {
    std::string group;      ///< e.g. 224.0.7.1
    std::string interface;  ///< interface name (eth0) or IPv4 address; empty: the kernel's choice

    friend bool operator==(const MulticastMembership&, const MulticastMembership&) = default;
};

/// Joins `membership` on the socket `fd`; throws std::system_error naming the group or the
/// interface on failure (a start-up error).
void join_group(int fd, const MulticastMembership& membership);

/// Leaves `membership` on the socket `fd`. Never throws: a group that cannot be left (its
/// interface went, and the kernel left it then) is logged.
void leave_group(int fd, const MulticastMembership& membership);

/// Holds the memberships of `groups` on a UDP socket bound to no port of EIP (an ephemeral one),
/// so the host receives the groups' datagrams while the socket itself is handed none of them.
/// Throws like join_group. Leaving happens when it is destroyed (the socket closes).
class GroupMemberships {
public:
    explicit GroupMemberships(const std::vector<MulticastMembership>& groups);
    ~GroupMemberships();
    GroupMemberships(const GroupMemberships&) = delete;
    GroupMemberships& operator=(const GroupMemberships&) = delete;

private:
    int fd_ = -1;
};

}  // namespace eip2mqtt::adapters::udp
