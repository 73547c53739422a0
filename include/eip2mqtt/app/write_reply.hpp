#pragma once
/// Where a write's result goes.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace eip2mqtt::app {

class Northbound;

/// The protocol a write came by: writes are counted by it (`writes_by_origin`).
enum class WriteOrigin : std::uint8_t { mqtt, sparkplug, commands };

inline constexpr std::size_t write_origin_count = 3;
inline constexpr std::array<WriteOrigin, write_origin_count> all_write_origins{
    WriteOrigin::mqtt, WriteOrigin::sparkplug, WriteOrigin::commands};

/// snake_case name, as used in metrics.
constexpr std::string_view to_string(WriteOrigin origin) {
    switch (origin) {
        case WriteOrigin::mqtt:
            return "mqtt";
        case WriteOrigin::sparkplug:
            return "sparkplug";
        case WriteOrigin::commands:
            return "commands";
    }
    return "unknown";
}

/// The northbound a write came from, and its protocol's address for the answer: for the JSON
/// tree, the MQTT 5 response topic with its correlation data, or the `…/set/result` topic.
struct WriteReply {
    std::string topic;
    std::string correlation_data;
    Northbound* origin = nullptr;  ///< nullptr: nobody to answer
    WriteOrigin via = WriteOrigin::mqtt;
};

}  // namespace eip2mqtt::app
