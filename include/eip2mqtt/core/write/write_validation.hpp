#pragma once
/// MQTT writes to produced tags (docs/mqtt-api.md "Writes"): what a write asks for, why
/// one is rejected, and the validation of a value against its tag. Pure: the JSON parsing that
/// yields a WriteInput lives in the MQTT adapter.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::core::write {

/// A JSON number or boolean as written by the client, before it meets a tag's type: `true`, `-2`,
/// `18446744073709551615`, `12.5`. Integers keep their exact value: every number whose exact
/// value is an integer of 64 bits comes as int64 or uint64, however it was spelt (`12.0`,
/// `1e3`), so a double is always a number with a fractional part or one beyond 64 bits. A
/// double cannot carry that itself: 9007199254740992.5 and -9223372036854775809 both round to
/// integers.
using ScalarInput = std::variant<bool, std::int64_t, std::uint64_t, double>;

/// A whole array: one scalar per element, as many as the tag's `count`.
struct ArrayInput {
    std::vector<ScalarInput> items;
    friend bool operator==(const ArrayInput&, const ArrayInput&) = default;
};

/// One element of an array: `{"index": 2, "value": 71.5}`.
struct ElementInput {
    std::uint16_t index = 0;
    ScalarInput value;
    friend bool operator==(const ElementInput&, const ElementInput&) = default;
};

/// What a write asks for: a scalar, a string's text (UTF-8), a whole array or one element.
using WriteInput =
    std::variant<bool, std::int64_t, std::uint64_t, double, std::string, ArrayInput, ElementInput>;

/// Why a write was rejected. Each value is also a metric label.
enum class WriteError : std::uint8_t {
    malformed,     ///< payload is not a JSON scalar or {"value": scalar} (or an object of them)
    unknown_tag,   ///< no such tag in the exchange
    read_only,     ///< the tag is not `writable`
    wrong_type,    ///< e.g. a string, or a number for a bit tag, or true for a real
    not_integer,   ///< a fractional number for an integer tag
    below_min,     ///< under the tag's `min`
    above_max,     ///< over the tag's `max`
    out_of_range,  ///< outside the type's own range (e.g. 70000 for an int)
    not_finite,    ///< NaN or infinity (never accepted from MQTT)
    retained,      ///< a retained message: a stale command must never fire
    expired,       ///< its MQTT 5 message expiry passed before it could be applied
    queue_full,    ///< the exchange's write queue is full; try again
    empty,         ///< a multi-tag write with no tag
    rate_limited,  ///< more writes to the tag than its `max_writes_per_s` allows
    bad_response_topic,  ///< the MQTT 5 response topic is not one the gateway may publish to
    too_large,           ///< the payload is over the size limit
    overlapping_tags,    ///< a multi-tag write sets two tags that share bits
    offline,             ///< a Sparkplug DCMD while the edge node is not born
    standby,             ///< the standby of a pair, with no live leader to answer it
};

inline constexpr auto write_error_names = enum_names<WriteError>(
    "malformed", "unknown_tag", "read_only", "wrong_type", "not_integer", "below_min", "above_max",
    "out_of_range", "not_finite", "retained", "expired", "queue_full", "empty", "rate_limited",
    "bad_response_topic", "too_large", "overlapping_tags", "offline", "standby");

inline constexpr std::size_t write_error_count = write_error_names.size();

constexpr std::string_view to_string(WriteError error) { return write_error_names.name_of(error); }

/// A rejection with the message the client gets back: `"above max 4000"`.
struct WriteRejection {
    WriteError error;
    std::string message;
};

/// Checks `input` against the tag (writable, type, the type's range, min/max) and converts it
/// to the tag's Value. Bits take true/false, and also 0/1. A scaled tag takes its value in
/// engineering units: checked against min and max, then made raw (plan::to_raw), refused
/// where it has no raw form. An array takes all its elements (a List) or one (its scalar, the
/// element named by element_of), each checked as a scalar tag's value; a string takes text with
/// a Latin-1 form of at most its length.
Result<plan::Value, WriteRejection> validate_write(const plan::TagSpec& tag,
                                                   const WriteInput& input);

/// A raw value for the tag, as the command port writes bytes: the type's range, and min and
/// max (of a scaled tag, against the engineering value the raw one reads as).
Result<plan::Value, WriteRejection> validate_raw_write(const plan::TagSpec& tag,
                                                       const plan::Value& raw);

/// The element an input writes alone; nullopt for a whole tag.
std::optional<std::uint16_t> element_of(const WriteInput& input);

/// One tag's validated new value, by index into the exchange plan's tags: the whole tag's, or
/// one element's of an array.
struct TagWrite {
    std::size_t tag_index = 0;
    plan::Value value;
    std::optional<std::uint16_t> element = std::nullopt;
};

/// A word and one of its bits in one write: which would win? Neither is written
/// (overlapping_tags); nullopt when no two of `writes` share bits.
std::optional<WriteRejection> overlap_rejection(const plan::ExchangePlan& plan,
                                                const std::vector<TagWrite>& writes);

/// A validated write of one or more tags of one produced exchange, applied atomically.
struct WriteBatch {
    std::uint64_t id = 0;  ///< assigned by the caller; returned when the batch was sent
    std::vector<TagWrite> writes;
};

}  // namespace eip2mqtt::core::write
