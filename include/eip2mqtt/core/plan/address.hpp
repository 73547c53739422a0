#pragma once
/// Tag addresses `byte.bit` (docs/protocol.md §3): offsets count from the first data byte.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace eip2mqtt::core::plan {

struct Address {
    std::uint16_t byte = 0;  ///< offset of the first data byte of the tag
    std::uint8_t bit = 0;    ///< 0..7 for bit tags, 0 for every other type

    friend bool operator==(const Address&, const Address&) = default;
};

/// Parses `B.b` or `B` (bit 0). Rejects signs, spaces, bit > 7 and byte > 65535.
std::optional<Address> parse_address(std::string_view text);

/// `B.b`.
std::string to_string(const Address& address);

}  // namespace eip2mqtt::core::plan
