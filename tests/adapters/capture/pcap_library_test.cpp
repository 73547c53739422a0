// libpcap loaded on first use: every function a capture calls is found in the library the build
// named, and the table is loaded once.

#include "adapters/capture/detail/pcap_library.hpp"

#include <gtest/gtest.h>

#include <string>

namespace eip2mqtt::adapters::capture::detail {
namespace EIP2MQTT_THIS_FILE {

TEST(PcapLibrary, TheSonameIsLibpcaps) {
    EXPECT_EQ(std::string(pcap_soname()).rfind("libpcap.so.", 0), 0u) << pcap_soname();
}

TEST(PcapLibrary, EveryFunctionACaptureCallsIsResolvedOnce) {
    const PcapLibrary& pcap = pcap_library();
    EXPECT_EQ(&pcap, &pcap_library());
    for (const void* function :
         {reinterpret_cast<const void*>(pcap.create),
          reinterpret_cast<const void*>(pcap.set_snaplen),
          reinterpret_cast<const void*>(pcap.set_immediate_mode),
          reinterpret_cast<const void*>(pcap.set_buffer_size),
          reinterpret_cast<const void*>(pcap.activate),
          reinterpret_cast<const void*>(pcap.statustostr),
          reinterpret_cast<const void*>(pcap.compile),
          reinterpret_cast<const void*>(pcap.setfilter),
          reinterpret_cast<const void*>(pcap.freecode),
          reinterpret_cast<const void*>(pcap.setnonblock),
          reinterpret_cast<const void*>(pcap.get_selectable_fd),
          reinterpret_cast<const void*>(pcap.datalink),
          reinterpret_cast<const void*>(pcap.dispatch), reinterpret_cast<const void*>(pcap.stats),
          reinterpret_cast<const void*>(pcap.geterr), reinterpret_cast<const void*>(pcap.close)}) {
        EXPECT_NE(function, nullptr);
    }
    // A call through the table reaches libpcap: a status code's text is its own.
    EXPECT_STREQ(pcap.statustostr(PCAP_ERROR_NO_SUCH_DEVICE), "No such device exists");
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::adapters::capture::detail
