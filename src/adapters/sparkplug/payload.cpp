// Sparkplug B payloads with the protobuf classes protoc generates from sparkplug_b.proto. As the
// specification says, Int8, Int16, Int32, UInt8 and UInt16 travel in int_value (the signed ones
// sign-extended to 32 bits), UInt32, Int64 and UInt64 in long_value (Int64 as two's complement).
// A command's UInt32 is read from either field: hosts differ.

#include "eip2mqtt/adapters/sparkplug/payload.hpp"

#include <limits>

#include "adapters/sparkplug/detail/array_bytes.hpp"
#include "sparkplug_b.pb.h"

namespace eip2mqtt::adapters::sparkplug {
namespace {

using detail::as_int64;
using detail::as_uint64;

using ProtoPayload = org::eclipse::tahu::protobuf::Payload;
using core::plan::TagType;
using core::plan::Value;

/// Bytes past which a command is refused unread: a host's DCMD for one exchange is small.
constexpr std::size_t max_command_bytes = 1 << 20;

bool is_signed_small(DataType type) {
    return type == DataType::int8 || type == DataType::int16 || type == DataType::int32;
}

bool is_unsigned_small(DataType type) {
    return type == DataType::uint8 || type == DataType::uint16;
}

/// Sets the value of a metric or a property (same field names in both messages).
template <class Proto>
void set_value(Proto& proto, DataType type, const Value& value) {
    if (const auto* text = std::get_if<core::plan::Text>(&value)) {
        proto.set_string_value(**text);
    } else if (const auto element = element_of(type)) {
        // Only a metric has bytes_value; properties are never arrays.
        if constexpr (requires { proto.set_bytes_value(std::string()); }) {
            const auto* items = core::plan::list_items(value);
            proto.set_bytes_value(items != nullptr ? detail::array_bytes(*element, *items) : "");
        }
    } else if (is_signed_small(type)) {
        proto.set_int_value(static_cast<std::uint32_t>(static_cast<std::int32_t>(as_int64(value))));
    } else if (is_unsigned_small(type)) {
        proto.set_int_value(static_cast<std::uint32_t>(as_uint64(value)));
    } else if (type == DataType::int64) {
        proto.set_long_value(static_cast<std::uint64_t>(as_int64(value)));
    } else if (type == DataType::uint32 || type == DataType::uint64) {
        proto.set_long_value(as_uint64(value));
    } else if (type == DataType::float32) {
        proto.set_float_value(static_cast<float>(core::plan::to_double(value)));
    } else if (type == DataType::float64) {
        proto.set_double_value(core::plan::to_double(value));
    } else {
        proto.set_boolean_value(core::plan::to_double(value) != 0.0);
    }
}

template <class Proto>
void set_value(Proto& proto, DataType type, const MetricValue& value) {
    if (const auto* text = std::get_if<std::string>(&value)) {
        proto.set_string_value(*text);
    } else {
        set_value(proto, type, std::get<Value>(value));
    }
}

void set_property(ProtoPayload::PropertySet& set, const Property& property) {
    set.add_keys(property.key);
    auto& value = *set.add_values();
    value.set_type(static_cast<std::uint32_t>(property.type));
    set_value(value, property.type, property.value);
}

/// The value of a command metric's field, read as `type` says; nullopt for a kind we do not
/// take.
std::optional<Value> read_value(const WireValue& wire, DataType type) {
    if (const auto* field = std::get_if<IntField>(&wire)) {
        if (is_signed_small(type))
            return Value{std::int64_t{static_cast<std::int32_t>(field->raw)}};
        if (is_unsigned_small(type) || type == DataType::uint32) {
            return Value{std::uint64_t{field->raw}};
        }
        return std::nullopt;
    }
    if (const auto* field = std::get_if<LongField>(&wire)) {
        if (type == DataType::int64) return Value{static_cast<std::int64_t>(field->raw)};
        if (type == DataType::uint32) {
            if (field->raw > std::numeric_limits<std::uint32_t>::max()) return std::nullopt;
            return Value{std::uint64_t{field->raw}};
        }
        if (type == DataType::uint64) return Value{std::uint64_t{field->raw}};
        return std::nullopt;
    }
    if (const auto* v = std::get_if<float>(&wire)) {
        return type == DataType::float32 ? std::optional<Value>(Value{*v}) : std::nullopt;
    }
    if (const auto* v = std::get_if<double>(&wire)) {
        return type == DataType::float64 ? std::optional<Value>(Value{*v}) : std::nullopt;
    }
    if (const auto* v = std::get_if<bool>(&wire)) {
        return type == DataType::boolean ? std::optional<Value>(Value{*v}) : std::nullopt;
    }
    return std::nullopt;
}

WireValue wire_value(const ProtoPayload::Metric& metric) {
    using Metric = ProtoPayload::Metric;
    if (metric.is_null()) return std::monostate{};
    switch (metric.value_case()) {
        case Metric::kIntValue:
            return IntField{metric.int_value()};
        case Metric::kLongValue:
            return LongField{metric.long_value()};
        case Metric::kFloatValue:
            return metric.float_value();
        case Metric::kDoubleValue:
            return metric.double_value();
        case Metric::kBooleanValue:
            return metric.boolean_value();
        default:
            return std::monostate{};
    }
}

}  // namespace

DataType array_of(DataType element) {
    if (element == DataType::boolean) return DataType::boolean_array;
    if (element == DataType::string) return DataType::string;
    const auto n = static_cast<std::uint32_t>(element);
    return static_cast<DataType>(static_cast<std::uint32_t>(DataType::int8_array) + n - 1);
}

std::optional<DataType> element_of(DataType array) {
    const auto n = static_cast<std::uint32_t>(array);
    const auto first = static_cast<std::uint32_t>(DataType::int8_array);
    if (n < first || n > static_cast<std::uint32_t>(DataType::boolean_array)) return std::nullopt;
    return static_cast<DataType>(n - first + 1);
}

DataType datatype_of(TagType type, bool array) {
    if (array) return array_of(datatype_of(type));
    switch (type) {
        case TagType::bit:
            return DataType::boolean;
        case TagType::byte:
            return DataType::uint8;
        case TagType::int_:
            return DataType::int16;
        case TagType::word:
            return DataType::uint16;
        case TagType::dint:
            return DataType::int32;
        case TagType::udint:
            return DataType::uint32;
        case TagType::lint:
            return DataType::int64;
        case TagType::real:
            return DataType::float32;
        case TagType::lreal:
            return DataType::float64;
        case TagType::string:
            return DataType::string;
    }
    return DataType::boolean;
}

std::string encode(const Payload& payload) {
    ProtoPayload proto;
    proto.set_timestamp(payload.timestamp_ms);
    if (payload.seq) proto.set_seq(*payload.seq);
    for (const auto& metric : payload.metrics) {
        auto& m = *proto.add_metrics();
        if (!metric.name.empty()) m.set_name(metric.name);
        if (metric.alias) m.set_alias(*metric.alias);
        m.set_timestamp(metric.timestamp_ms);
        m.set_datatype(static_cast<std::uint32_t>(metric.datatype));
        if (metric.historical) m.set_is_historical(true);
        if (metric.value) {
            set_value(m, metric.datatype, *metric.value);
        } else {
            m.set_is_null(true);
        }
        if (!metric.properties.empty()) {
            auto& properties = *m.mutable_properties();
            for (const auto& property : metric.properties) set_property(properties, property);
        }
    }
    return proto.SerializeAsString();
}

std::optional<Value> CommandMetric::value_as(DataType type) const { return read_value(wire, type); }

core::Result<std::vector<CommandMetric>, std::string> decode_command(std::string_view bytes) {
    if (bytes.size() > max_command_bytes) {
        return core::fail("a command of " + std::to_string(bytes.size()) + " bytes (limit " +
                          std::to_string(max_command_bytes) + ")");
    }
    ProtoPayload proto;
    if (!proto.ParseFromArray(bytes.data(), static_cast<int>(bytes.size()))) {
        return core::fail(std::string("not a Sparkplug B payload"));
    }
    std::vector<CommandMetric> metrics;
    metrics.reserve(static_cast<std::size_t>(proto.metrics_size()));
    for (const auto& m : proto.metrics()) {
        CommandMetric metric;
        metric.name = m.name();
        if (m.has_alias()) metric.alias = m.alias();
        if (m.has_datatype()) {
            const auto type = m.datatype();
            if (type >= static_cast<std::uint32_t>(DataType::int8) &&
                type <= static_cast<std::uint32_t>(DataType::string)) {
                metric.datatype = static_cast<DataType>(type);
            }
        }
        metric.wire = wire_value(m);
        if (metric.datatype) metric.value = metric.value_as(*metric.datatype);
        metrics.push_back(std::move(metric));
    }
    return metrics;
}

}  // namespace eip2mqtt::adapters::sparkplug
