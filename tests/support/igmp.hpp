#pragma once
/// The multicast groups the kernel has joined, as /proc/net/igmp lists them (one network
/// namespace: every socket's memberships, whichever process made them).

#include <string>

namespace eip2mqtt::test {

/// Whether `group` (dotted IPv4) is joined on `interface` (a name: `lo`).
bool igmp_joined(const std::string& interface, const std::string& group);

/// A multicast group of 239.0.0.0/8 (administratively scoped) no other test process picks: its
/// last two bytes are this process's id, the second `index` (0..255).
std::string test_multicast_group(int index);

}  // namespace eip2mqtt::test
