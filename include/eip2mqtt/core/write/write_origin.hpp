#pragma once
/// The protocol a write came by: writes are counted by it (`writes_by_origin`). Pure.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace eip2mqtt::core::write {

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

}  // namespace eip2mqtt::core::write
