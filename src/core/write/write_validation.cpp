#include "eip2mqtt/core/write/write_validation.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <compare>
#include <limits>
#include <utility>

#include "core/write/detail/composite_writes.hpp"
#include "eip2mqtt/core/plan/overlap.hpp"
#include "eip2mqtt/core/plan/scaling.hpp"

namespace eip2mqtt::core::write {
namespace {

using plan::TagType;

// 2^63 and 2^64 are exact doubles; int64 max and uint64 max are not.
constexpr double two_pow_63 = 9223372036854775808.0;

/// Shortest text that reads back to the same double, as the YAML wrote it: 4000, 0.5, 1e+20.
template <class Float>
std::string shortest(Float value) {
    std::array<char, 64> buffer{};
    const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
    return std::string(buffer.data(), result.ptr);
}

WriteRejection reject(WriteError error, std::string message) { return {error, std::move(message)}; }

/// The exact range of an integer type.
struct IntRange {
    std::int64_t min;
    std::uint64_t max;
};

IntRange int_range(TagType type) {
    switch (type) {
        case TagType::byte:
            return {0, std::numeric_limits<std::uint8_t>::max()};
        case TagType::int_:
            return {std::numeric_limits<std::int16_t>::min(),
                    std::numeric_limits<std::int16_t>::max()};
        case TagType::word:
            return {0, std::numeric_limits<std::uint16_t>::max()};
        case TagType::dint:
            return {std::numeric_limits<std::int32_t>::min(),
                    std::numeric_limits<std::int32_t>::max()};
        case TagType::udint:
            return {0, std::numeric_limits<std::uint32_t>::max()};
        case TagType::lint:
            return {std::numeric_limits<std::int64_t>::min(),
                    std::numeric_limits<std::int64_t>::max()};
        default:
            return {0, 1};  // bit
    }
}

WriteRejection out_of_range(TagType type) {
    std::string range;
    if (type == TagType::real) {
        const float max = std::numeric_limits<float>::max();
        range = shortest(-max) + ".." + shortest(max);
    } else {
        const IntRange r = int_range(type);
        range = std::to_string(r.min) + ".." + std::to_string(r.max);
    }
    return reject(WriteError::out_of_range,
                  "out of range for " + std::string(plan::to_string(type)) + " (" + range + ")");
}

bool is_signed(TagType type) {
    return type == TagType::int_ || type == TagType::dint || type == TagType::lint;
}

/// An integer input converted to an integer tag's Value, with exact range checks.
template <class Int>
Result<plan::Value, WriteRejection> integer_value(TagType type, Int v) {
    const IntRange r = int_range(type);
    if (std::cmp_less(v, r.min) || std::cmp_greater(v, r.max)) return fail(out_of_range(type));
    if (is_signed(type)) return plan::Value{static_cast<std::int64_t>(v)};
    return plan::Value{static_cast<std::uint64_t>(v)};
}

Result<plan::Value, WriteRejection> to_integer_tag(TagType type, const ScalarInput& input) {
    if (const auto* v = std::get_if<std::int64_t>(&input)) return integer_value(type, *v);
    if (const auto* v = std::get_if<std::uint64_t>(&input)) return integer_value(type, *v);
    if (const auto* d = std::get_if<double>(&input)) {
        // WriteInput: integers of 64 bits never come as doubles, so a double is a fraction,
        // or an integer beyond every integer tag's range. Only the magnitude tells which: a
        // fraction's double may be a whole number (9007199254740992.5 rounds to 2^53).
        if (std::fabs(*d) >= two_pow_63) return fail(out_of_range(type));
        return fail(reject(WriteError::not_integer, "expected an integer"));
    }
    return fail(reject(WriteError::wrong_type, "expected a number"));
}

Result<plan::Value, WriteRejection> to_bit_tag(const ScalarInput& input) {
    if (const auto* b = std::get_if<bool>(&input)) return plan::Value{*b};
    // Bits also take the integers 0 and 1; any other integer is outside a bit's range, and a
    // float (even 1.0) is not how anyone writes a bit.
    if (const auto* v = std::get_if<std::int64_t>(&input)) {
        if (*v == 0 || *v == 1) return plan::Value{*v == 1};
        return fail(out_of_range(TagType::bit));
    }
    if (const auto* v = std::get_if<std::uint64_t>(&input)) {
        if (*v <= 1) return plan::Value{*v == 1};
        return fail(out_of_range(TagType::bit));
    }
    return fail(reject(WriteError::wrong_type, "expected true or false"));
}

Result<plan::Value, WriteRejection> to_float_tag(TagType type, const ScalarInput& input) {
    if (std::holds_alternative<bool>(input)) {
        return fail(reject(WriteError::wrong_type, "expected a number"));
    }
    const double d = std::visit([](auto v) { return static_cast<double>(v); }, input);
    if (type == TagType::lreal) return plan::Value{d};
    const double max = std::numeric_limits<float>::max();
    if (d < -max || d > max) return fail(out_of_range(type));
    return plan::Value{static_cast<float>(d)};
}

/// Three-way comparison of an integer with a double, exact where a cast to double would round
/// (lint values beyond 2^53).
std::partial_ordering compare(std::int64_t v, double limit) {
    if (std::isnan(limit)) return std::partial_ordering::unordered;
    if (limit >= two_pow_63) return std::partial_ordering::less;
    if (limit < -two_pow_63) return std::partial_ordering::greater;
    const double floor = std::floor(limit);
    const auto f = static_cast<std::int64_t>(floor);  // exact: floor is in int64's range
    if (v < f) return std::partial_ordering::less;
    if (v > f) return std::partial_ordering::greater;  // v >= floor + 1 > limit
    return floor == limit ? std::partial_ordering::equivalent : std::partial_ordering::less;
}

/// The value compared with a tag's min or max. Integer values are compared exactly; the input,
/// not its binary32 rounding, is what a real's limits are checked against.
std::partial_ordering compare(const plan::Value& value, const ScalarInput& input, double limit) {
    if (const auto* v = std::get_if<std::int64_t>(&value)) return compare(*v, limit);
    if (const auto* v = std::get_if<std::uint64_t>(&value)) {
        // Unsigned tags end at udint: every value fits an int64.
        return compare(static_cast<std::int64_t>(*v), limit);
    }
    if (std::holds_alternative<float>(value)) {
        return std::visit([](auto v) { return static_cast<double>(v); }, input) <=> limit;
    }
    return plan::to_double(value) <=> limit;
}

ScalarInput raw_input(const plan::Value& value) {
    return std::visit(
        [](const auto& v) -> ScalarInput {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, float>) {
                return static_cast<double>(v);
            } else if constexpr (std::is_same_v<V, plan::Text> || std::is_same_v<V, plan::List>) {
                return false;  // never asked: composites are checked before
            } else {
                return v;
            }
        },
        value);
}

/// A scaled tag's engineering value against its min and max; nullopt within them.
std::optional<WriteRejection> outside_limits(const plan::TagSpec& tag, double eu) {
    if (const auto& min = tag.min(); min && eu < *min) {
        return reject(WriteError::below_min, "below min " + shortest(*min));
    }
    if (const auto& max = tag.max(); max && eu > *max) {
        return reject(WriteError::above_max, "above max " + shortest(*max));
    }
    return std::nullopt;
}

/// A write in engineering units: checked against min and max, then made raw.
Result<plan::Value, WriteRejection> to_scaled_tag(const plan::TagSpec& tag,
                                                  const ScalarInput& input) {
    if (std::holds_alternative<bool>(input)) {
        return fail(reject(WriteError::wrong_type, "expected a number"));
    }
    const double eu = std::visit([](auto v) { return static_cast<double>(v); }, input);
    if (auto outside = outside_limits(tag, eu)) return fail(std::move(*outside));
    auto raw = plan::to_raw(eu, *tag.scale(), tag.type);
    if (raw) return std::move(raw).value();
    if (raw.error() == plan::RawRefusal::below_zero) {
        return fail(reject(WriteError::out_of_range,
                           "below the square root's zero: no raw value reads as it"));
    }
    auto refusal = out_of_range(tag.type);
    refusal.message = "raw value " + refusal.message;
    return fail(std::move(refusal));
}

/// A number or boolean for one value of the tag (the tag's, or one element's of an array).
Result<plan::Value, WriteRejection> validate_scalar(const plan::TagSpec& tag,
                                                    const ScalarInput& input) {
    if (const auto* d = std::get_if<double>(&input); d != nullptr && !std::isfinite(*d)) {
        return fail(reject(WriteError::not_finite, "not a finite number"));
    }
    if (tag.scale()) return to_scaled_tag(tag, input);

    auto converted = tag.type == TagType::bit     ? to_bit_tag(input)
                     : plan::is_integer(tag.type) ? to_integer_tag(tag.type, input)
                                                  : to_float_tag(tag.type, input);
    if (!converted) return converted;

    // Limits come after the type's own checks, so "expected an integer" wins over "above max".
    if (const auto& min = tag.min(); min && compare(*converted, input, *min) < 0) {
        return fail(reject(WriteError::below_min, "below min " + shortest(*min)));
    }
    if (const auto& max = tag.max(); max && compare(*converted, input, *max) > 0) {
        return fail(reject(WriteError::above_max, "above max " + shortest(*max)));
    }
    return converted;
}

}  // namespace

Result<plan::Value, WriteRejection> validate_write(const plan::TagSpec& tag,
                                                   const WriteInput& input) {
    if (!tag.writable) return fail(reject(WriteError::read_only, "tag is read-only"));
    if (tag.type == TagType::string) return detail::to_string_tag(tag, input);
    if (tag.is_array()) {
        return detail::to_array_tag(
            tag, input, [&tag](const ScalarInput& item) { return validate_scalar(tag, item); });
    }
    const auto scalar = detail::as_scalar(input);
    if (!scalar) return fail(reject(WriteError::wrong_type, detail::not_scalar(input)));
    return validate_scalar(tag, *scalar);
}

Result<plan::Value, WriteRejection> validate_raw_write(const plan::TagSpec& tag,
                                                       const plan::Value& raw) {
    if (!tag.writable) return fail(reject(WriteError::read_only, "tag is read-only"));
    if (std::holds_alternative<plan::Text>(raw)) return raw;  // bytes as they are
    if (const auto* items = plan::list_items(raw)) {
        for (const auto& item : *items) {
            if (auto checked = validate_raw_write(tag, item); !checked) return checked;
        }
        return raw;
    }
    if (!tag.scale()) return validate_scalar(tag, raw_input(raw));
    if (!std::isfinite(plan::to_double(raw))) {
        return fail(reject(WriteError::not_finite, "not a finite number"));
    }
    const double eu = plan::to_double(plan::to_engineering(raw, *tag.scale()).value);
    if (auto outside = outside_limits(tag, eu)) return fail(std::move(*outside));
    return raw;
}

std::optional<std::uint16_t> element_of(const WriteInput& input) {
    if (const auto* element = std::get_if<ElementInput>(&input)) return element->index;
    return std::nullopt;
}

std::optional<WriteRejection> overlap_rejection(const plan::ExchangePlan& plan,
                                                const std::vector<TagWrite>& writes) {
    if (writes.size() < 2) return std::nullopt;
    std::vector<plan::BitSpan> spans;
    spans.reserve(writes.size());
    for (const auto& write : writes)
        spans.push_back(plan::bit_span(plan.tags[write.tag_index].spec));
    const auto overlaps = plan::find_overlaps(spans, 1);
    if (overlaps.listed.empty()) return std::nullopt;
    const auto& pair = overlaps.listed.front();
    return WriteRejection{WriteError::overlapping_tags,
                          "tags " + plan.tags[writes[pair.first].tag_index].spec.name + " and " +
                              plan.tags[writes[pair.second].tag_index].spec.name +
                              " share bytes; write them in separate messages"};
}

}  // namespace eip2mqtt::core::write
