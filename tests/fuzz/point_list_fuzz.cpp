// Fuzzes the SCADA point-list CSV parser (docs/protocol.md §6).

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "eip2mqtt/core/config/point_list.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    const auto list = eip2mqtt::core::config::parse_point_list(text, "fuzz.csv");
    for (const auto& row : list.rows) {
        if (row.tag.address.bit > 7) __builtin_trap();
    }
    return 0;
}
