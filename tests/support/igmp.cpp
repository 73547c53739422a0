#include "tests/support/igmp.hpp"

#include <arpa/inet.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace eip2mqtt::test {

bool igmp_joined(const std::string& interface, const std::string& group) {
    // The kernel prints each group's address as the 32-bit integer it holds in network order,
    // in hex: on a little-endian machine 239.255.42.7 is 072AFFEF.
    char wanted[9];
    std::snprintf(wanted, sizeof wanted, "%08X", static_cast<unsigned>(::inet_addr(group.c_str())));
    std::ifstream file("/proc/net/igmp");
    std::string line;
    std::string device;
    while (std::getline(file, line)) {
        std::istringstream fields(line);
        if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0]))) {
            // "1\tlo        :     2      V3": an interface, whose groups follow.
            std::string index;
            fields >> index >> device;
            if (!device.empty() && device.back() == ':') device.pop_back();
            continue;
        }
        std::string address;
        fields >> address;
        if (device == interface && address == wanted) return true;
    }
    return false;
}

std::string test_multicast_group(int index) {
    const auto pid = static_cast<unsigned>(::getpid());
    return "239." + std::to_string(index) + "." + std::to_string((pid >> 8) & 0xFF) + "." +
           std::to_string(pid & 0xFF);
}

}  // namespace eip2mqtt::test
