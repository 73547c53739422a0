// Fuzzes engineering values: a scale (kind, ranges, gain, offset, clamp, type_eu) and a wire
// type from the first bytes, a raw value decoded from the rest as the wire carries it, then the
// scale both ways. Scales the configuration refuses (equal ends, gain 0, non-finite numbers)
// are skipped, as the gateway never runs them.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "eip2mqtt/core/plan/scaling.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"

namespace {

using namespace eip2mqtt::core::plan;

double take_double(const std::uint8_t*& data, std::size_t& size) {
    double d = 0;
    if (size >= sizeof d) {
        std::memcpy(&d, data, sizeof d);
        data += sizeof d;
        size -= sizeof d;
    }
    return d;
}

bool acceptable(const Scaling& s) {
    if (s.kind == ScaleKind::gain_offset) {
        return std::isfinite(s.gain) && s.gain != 0 && std::isfinite(s.offset);
    }
    const bool finite = std::isfinite(s.raw.lo) && std::isfinite(s.raw.hi) &&
                        std::isfinite(s.eu.lo) && std::isfinite(s.eu.hi);
    if (!finite || s.raw.lo == s.raw.hi || s.eu.lo == s.eu.hi) return false;
    return s.kind != ScaleKind::square_root || (s.raw.lo >= 0 && s.raw.hi >= 0);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size < 3) return 0;
    constexpr TagType wires[] = {TagType::byte,  TagType::int_, TagType::word, TagType::dint,
                                 TagType::udint, TagType::real, TagType::lint, TagType::lreal};
    const TagType wire = wires[data[0] % 8];
    Scaling s;
    s.kind = static_cast<ScaleKind>(data[1] % 3);
    s.clamp = (data[1] & 0x10) != 0 && s.kind != ScaleKind::gain_offset;
    if (data[2] % 9 != 8) s.eu_type = wires[data[2] % 8];
    data += 3;
    size -= 3;
    s.raw = {take_double(data, size), take_double(data, size)};
    s.eu = {take_double(data, size), take_double(data, size)};
    s.gain = take_double(data, size);
    s.offset = take_double(data, size);
    if (!acceptable(s) || size < size_of(wire)) return 0;

    const auto raw = decode_value(std::as_bytes(std::span(data, size)), wire, Address{0, 0});
    const auto eu = to_engineering(raw, s);
    const double value = to_double(eu.value);
    const auto span = eu_span(s);
    // Clamped, a value stays within eu (as its own type rounds the ends).
    if (s.clamp && !s.eu_type && !std::isnan(value) && (value < span->lo || value > span->hi)) {
        __builtin_trap();
    }
    if (std::isnan(to_double(raw)) && eu.limit != Limit::none) __builtin_trap();
    // The inverse of any finite engineering value either refuses or gives a value of the wire's
    // type that reads back as a number.
    if (std::isfinite(value)) {
        const auto back = to_raw(value, s, wire);
        if (back && std::isnan(to_double(to_engineering(back.value(), s).value))) __builtin_trap();
    }
    return 0;
}
