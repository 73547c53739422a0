#pragma once
/// The test vectors of docs/protocol.md §8 as hex, and hex <-> bytes helpers for core tests.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::test {

/// Bytes of a hex string (upper or lower case, no separators). Throws on bad input so that a
/// mistyped vector fails its test instead of silently shrinking.
inline std::vector<std::byte> from_hex(std::string_view hex) {
    const auto nibble = [](char c) -> unsigned {
        if (c >= '0' && c <= '9') return static_cast<unsigned>(c - '0');
        if (c >= 'a' && c <= 'f') return static_cast<unsigned>(c - 'a' + 10);
        if (c >= 'A' && c <= 'F') return static_cast<unsigned>(c - 'A' + 10);
        throw std::invalid_argument("bad hex digit");
    };
    if (hex.size() % 2 != 0) throw std::invalid_argument("odd hex length");
    std::vector<std::byte> out;
    out.reserve(hex.size() / 2);
    for (std::size_t i = 0; i < hex.size(); i += 2) {
        out.push_back(static_cast<std::byte>(nibble(hex[i]) << 4 | nibble(hex[i + 1])));
    }
    return out;
}

/// Lower-case hex of bytes, for readable assertion messages.
inline std::string to_hex(std::span<const std::byte> bytes) {
    static constexpr char digits[] = "0123456789abcdef";
    std::string out;
    for (std::byte b : bytes) {
        const auto v = std::to_integer<unsigned>(b);
        out += digits[v >> 4];
        out += digits[v & 0xF];
    }
    return out;
}

/// Seconds since 1970 UTC of a civil date and time, to state the vectors' timestamps as the spec
/// writes them.
inline std::uint32_t utc_seconds(int y, unsigned mo, unsigned d, int h, int mi, int s) {
    using namespace std::chrono;
    const auto t = sys_days{year{y} / month{mo} / day{d}} + hours{h} + minutes{mi} + seconds{s};
    return static_cast<std::uint32_t>(t.time_since_epoch().count());
}

namespace vectors {

/// V1: a point list sent with the seed-style integer Real (data 15 bytes).
inline constexpr std::string_view v1 =
    "0d016c00c0a8010101000000be2e0b6500000000000000000000000000000000"
    "e75a006c01010060960e0000000000";

/// V2: the same values with a correct REAL (real at 3.0 = 65900.0).
inline constexpr std::string_view v2 =
    "0d016c00c0a8010101000000be2e0b6500000000000000000000000000000000"
    "e75a0000b6804760960e0000000000";

/// V3: four REALs (0.0, 180.0, 109.0, 110.0).
inline constexpr std::string_view v3 =
    "0d01294ec0a865d3030000001ac7d26468becb21000000000000000000000000"
    "00000000000034430000da420000dc42";

/// V4: the first 20 header bytes.
inline constexpr std::string_view v4 = "0d019136ac1715b0010000007332dd6374168e0f";

/// V5: signature major 2, minor 5, no timestamp, no data.
inline constexpr std::string_view v5 =
    "0d0101000a000005070000000000000000000000000000000502000000000000";

}  // namespace vectors
}  // namespace eip2mqtt::test
