#pragma once
/// Engineering values (docs/configuration.md "Engineering values"): what a tag's raw wire value
/// means in the plant's units, and the raw value a write in those units becomes. Pure
/// arithmetic; the configuration checks that a Scaling is sound before it reaches here.

#include <cstdint>
#include <optional>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::core::plan {

/// How raw becomes engineering: linear between two ranges, the square root of the raw range's
/// fraction (flow from a differential pressure), or eu = raw x gain + offset.
enum class ScaleKind : std::uint8_t { linear, square_root, gain_offset };

inline constexpr auto scale_kind_names = enum_names<ScaleKind>("linear", "sqrt", "gain");

constexpr std::string_view to_string(ScaleKind kind) { return scale_kind_names.name_of(kind); }

/// Two ends, in the order configured: `lo` maps onto the other range's `lo`. Either may be the
/// larger (a reversed range inverts the value).
struct ScaleRange {
    double lo = 0.0;
    double hi = 1.0;

    friend bool operator==(const ScaleRange&, const ScaleRange&) = default;
};

/// A tag's `scale:`.
struct Scaling {
    ScaleKind kind = ScaleKind::linear;
    ScaleRange raw;     ///< linear and square_root
    ScaleRange eu;      ///< linear and square_root
    double gain = 1.0;  ///< gain_offset; never 0
    double offset = 0.0;
    bool clamp = false;  ///< hold the value at eu's ends (linear and square_root)
    /// The type the engineering value is published as (`type_eu`): integers are rounded half
    /// away from zero; nullopt publishes a double.
    std::optional<TagType> eu_type;

    friend bool operator==(const Scaling&, const Scaling&) = default;
};

/// Where a raw value fell outside the raw range: beyond its `lo` end or its `hi` end.
enum class Limit : std::uint8_t { none, low, high };

inline constexpr auto limit_names = enum_names<Limit>("none", "low", "high");

constexpr std::string_view to_string(Limit limit) { return limit_names.name_of(limit); }

struct Engineering {
    Value value;
    Limit limit = Limit::none;
};

/// The engineering value of `raw` (a value decode_tag gave; bits and strings are never scaled;
/// an array's elements each, flagged high if any is high, else low if any is low). NaN
/// stays NaN. Below `raw.lo` a square root reads `eu.lo`; beyond either end a linear value goes
/// on along its line unless `clamp` holds it at that end of `eu`. An integer `eu_type`
/// saturates at its own ends, flagged as a limit.
Engineering to_engineering(const Value& raw, const Scaling& scaling);

/// The engineering range a percent deadband and `_meta` take: `eu` in the order low, high;
/// nullopt for gain_offset, which has none.
std::optional<ScaleRange> eu_span(const Scaling& scaling);

/// Why an engineering value has no raw form.
enum class RawRefusal : std::uint8_t {
    below_zero,    ///< under the square root's zero: no raw value reads as it
    out_of_range,  ///< its raw form does not fit the wire type
};

/// The raw value of `wire` that `eu` becomes (to_engineering's inverse; integers rounded half
/// away from zero), in the Value alternative decode_value gives `wire`. `eu` is finite.
Result<Value, RawRefusal> to_raw(double eu, const Scaling& scaling, TagType wire);

}  // namespace eip2mqtt::core::plan
