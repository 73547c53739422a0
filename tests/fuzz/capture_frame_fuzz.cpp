// Fuzzes the decoding of captured frames (sniff's passive capture reads whatever the network
// carries): the first byte picks the link type, the rest is the frame.

#include <cstddef>
#include <cstdint>
#include <span>

#include "eip2mqtt/adapters/capture/frame.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace eip2mqtt::adapters::capture;
    if (size == 0) return 0;
    constexpr int link_types[] = {link::null,      link::ethernet, link::raw,        link::loop,
                                  link::linux_sll, link::ipv4,     link::linux_sll2, 42};
    const int link_type = link_types[data[0] % (sizeof link_types / sizeof link_types[0])];
    const std::span<const std::byte> frame(reinterpret_cast<const std::byte*>(data + 1), size - 1);
    const auto decoded = decode_frame(link_type, frame);
    if (!decoded) {
        (void)to_string(decoded.error());
        return 0;
    }
    // The payload lies inside the frame.
    const auto& payload = decoded->payload;
    if (payload.data() < frame.data() ||
        payload.data() + payload.size() > frame.data() + frame.size()) {
        __builtin_trap();
    }
    return 0;
}
