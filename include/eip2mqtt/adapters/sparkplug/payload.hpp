#pragma once
/// Sparkplug B payloads, in our terms: what the gateway puts in a birth or a data
/// message, and what a host's command asks, encoded and decoded with protobuf. Decoding never
/// throws: hostile bytes give an error text.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::adapters::sparkplug {

/// The specification's datatype numbers (those a metric of ours can have, and String).
enum class DataType : std::uint32_t {
    int8 = 1,
    int16 = 2,
    int32 = 3,
    int64 = 4,
    uint8 = 5,
    uint16 = 6,
    uint32 = 7,
    uint64 = 8,
    float32 = 9,
    float64 = 10,
    boolean = 11,
    string = 12,
    // Arrays (Sparkplug B 3.0): the elements packed little-endian in bytes_value.
    int8_array = 22,
    int16_array = 23,
    int32_array = 24,
    int64_array = 25,
    uint8_array = 26,
    uint16_array = 27,
    uint32_array = 28,
    uint64_array = 29,
    float_array = 30,
    double_array = 31,
    boolean_array = 32,
};

/// The array type of a scalar type (Int32 -> Int32Array); String for a String.
DataType array_of(DataType element);
/// The element type of an array type (Int32Array -> Int32); nullopt for a scalar type.
std::optional<DataType> element_of(DataType array);

/// bit -> Boolean, byte -> UInt8, int -> Int16, word -> UInt16, dint -> Int32, udint -> UInt32,
/// lint -> Int64, real -> Float, lreal -> Double, string -> String; with `array`, the array
/// type of each (BooleanArray...).
DataType datatype_of(core::plan::TagType type, bool array = false);

/// A metric's or a property's value: a tag's, or a text (an exchange's state, a unit).
using MetricValue = std::variant<core::plan::Value, std::string>;

/// A metric property (engineering unit, description, writable, limits).
struct Property {
    std::string key;
    DataType type = DataType::string;
    MetricValue value;
};

struct Metric {
    std::string name;  ///< empty: referred to by alias only (DDATA)
    std::optional<std::uint64_t> alias;
    std::uint64_t timestamp_ms = 0;
    DataType datatype = DataType::boolean;
    /// nullopt: is_null (a value the gateway does not have).
    std::optional<MetricValue> value;
    bool historical = false;
    std::vector<Property> properties;
};

struct Payload {
    std::uint64_t timestamp_ms = 0;
    std::optional<std::uint64_t> seq;  ///< absent in NCMD, DCMD and STATE-like payloads
    std::vector<Metric> metrics;
};

/// The protobuf bytes of `payload`.
std::string encode(const Payload& payload);

/// A command metric's value as the payload carries it, before a datatype gives it a meaning:
/// which field holds it (int_value and long_value are both unsigned on the wire).
struct IntField {
    std::uint32_t raw = 0;
    friend bool operator==(const IntField&, const IntField&) = default;
};
struct LongField {
    std::uint64_t raw = 0;
    friend bool operator==(const LongField&, const LongField&) = default;
};
using WireValue = std::variant<std::monostate, IntField, LongField, float, double, bool>;

/// A metric of a host's command (NCMD, DCMD): what it names and the value it carries. Values of
/// other kinds than ours (strings, datasets) are refused.
struct CommandMetric {
    std::string name;
    std::optional<std::uint64_t> alias;
    std::optional<DataType> datatype;
    /// Read as `datatype` says; nullopt: is_null, no value, a value of another kind, or no
    /// datatype (value_as then).
    std::optional<core::plan::Value> value;
    WireValue wire;  ///< monostate: is_null or no value of a kind we read

    /// The value read as `type` says. Sparkplug B 3.0 recommends commands without datatypes
    /// (a host that uses aliases sends alias and value alone): the datatype is then that of the
    /// metric it names, in the birth.
    std::optional<core::plan::Value> value_as(DataType type) const;
};

/// The metrics of a command; an error text for bytes that are not a Sparkplug payload.
core::Result<std::vector<CommandMetric>, std::string> decode_command(std::string_view bytes);

}  // namespace eip2mqtt::adapters::sparkplug
