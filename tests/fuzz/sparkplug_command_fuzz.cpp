// Fuzzes the reading of a Sparkplug host's commands (NCMD, DCMD), which come from anyone allowed
// to publish on the node's command topics: hostile protobuf must give an error or metrics, never
// an exception or a crash.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "eip2mqtt/adapters/sparkplug/payload.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    const auto metrics = eip2mqtt::adapters::sparkplug::decode_command(bytes);
    if (metrics) {
        for (const auto& metric : metrics.value()) {
            // A value is only read through a datatype we know.
            if (metric.value && !metric.datatype) __builtin_trap();
        }
    }
    return 0;
}
