// The passive capture behind `sniff`: the frames it asks the kernel for, what it tells an
// operator without the privilege to capture, and a --bind that is no address refused before
// any capture opens.

#include "app/cli/detail/sniff_capture.hpp"

#include <gtest/gtest.h>

#include <boost/asio/io_context.hpp>
#include <filesystem>
#include <sstream>
#include <string>

namespace eip2mqtt::app::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(SniffCapture, TheFilterTakesDatagramsToThePortAndToTheBoundAddressWhenGiven) {
    EXPECT_EQ(capture_filter(18246, ""), "ip and udp dst port 18246");
    EXPECT_EQ(capture_filter(7937, "10.0.0.5"), "ip and udp dst port 7937 and dst host 10.0.0.5");
}

TEST(SniffCapture, ThePrivilegeHelpSaysWhyAndNamesThisBinaryInTheSetcapCommand) {
    const auto help = capture_privilege_help("eth0", "Operation not permitted");
    const auto binary = std::filesystem::read_symlink("/proc/self/exe").string();
    EXPECT_EQ(help.find("eip2mqtt sniff: capturing on 'eth0' needs the CAP_NET_RAW capability, "
                        "which this process lacks (Operation not permitted).\n"),
              0u)
        << help;
    EXPECT_NE(help.find("  sudo eip2mqtt sniff ...\n"), std::string::npos) << help;
    EXPECT_NE(help.find("  sudo setcap cap_net_raw,cap_net_admin+eip " + binary + "\n"),
              std::string::npos)
        << help;
}

TEST(SniffCapture, ABindThatIsNoIpv4AddressOpensNoCapture) {
    boost::asio::io_context loop;
    SniffOptions options;
    options.bind = "gateway.local";
    std::ostringstream err;
    EXPECT_EQ(open_capture(loop.get_executor(), options, 18246, err), nullptr);
    EXPECT_EQ(err.str(), "eip2mqtt sniff: --bind 'gateway.local' is not an IPv4 address\n");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::app::detail
