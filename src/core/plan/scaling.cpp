#include "eip2mqtt/core/plan/scaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace eip2mqtt::core::plan {
namespace {

// 2^63: the first double past int64's range (its max rounds up to it).
constexpr double two_pow_63 = 9223372036854775808.0;

bool is_signed(TagType type) {
    return type == TagType::int_ || type == TagType::dint || type == TagType::lint;
}

/// Whether an integral double fits an integer type exactly.
bool fits(double whole, TagType type) {
    if (type == TagType::lint) return whole >= -two_pow_63 && whole < two_pow_63;
    return whole >= type_min(type) && whole <= type_max(type);
}

/// An integral double that fits `type`, as the Value alternative decode_value gives it.
Value integer_value(double whole, TagType type) {
    if (is_signed(type)) return Value{static_cast<std::int64_t>(whole)};
    return Value{static_cast<std::uint64_t>(whole)};
}

/// An integer type's lowest or highest value (lint's, which no double holds, exactly).
Value type_end(TagType type, bool high) {
    if (type == TagType::lint) {
        return Value{high ? std::numeric_limits<std::int64_t>::max()
                          : std::numeric_limits<std::int64_t>::min()};
    }
    return integer_value(high ? type_max(type) : type_min(type), type);
}

/// Where `raw` falls on the raw range: 0 at `lo`, 1 at `hi`.
double fraction(double raw, const ScaleRange& range) {
    return (raw - range.lo) / (range.hi - range.lo);
}

Engineering along_range(double raw, const Scaling& s) {
    double t = fraction(raw, s.raw);
    // NaN stays NaN: std::lerp gives an end of the range for a NaN t when that range falls.
    if (std::isnan(t)) return {Value{t}, Limit::none};
    Limit limit = Limit::none;
    if (t < 0.0) {
        limit = Limit::low;
        // A square root has nothing below its zero: a flow meter reads no flow there.
        if (s.clamp || s.kind == ScaleKind::square_root) t = 0.0;
    } else if (t > 1.0) {
        limit = Limit::high;
        if (s.clamp) t = 1.0;
    }
    if (s.kind == ScaleKind::square_root) t = std::sqrt(t);
    // An infinite raw value goes on along the line to an infinity of the span's sign, where
    // std::lerp would give NaN (inf x 0) for a span across zero.
    if (std::isinf(t)) return {Value{(s.eu.hi - s.eu.lo) * t}, limit};
    // std::lerp is exact at both ends and monotonic between them.
    return {Value{std::lerp(s.eu.lo, s.eu.hi, t)}, limit};
}

/// The engineering double in `eu_type`: rounded and saturated for integers, flagged where it
/// saturates. NaN and infinities stay doubles: no integer holds them.
Engineering as_eu_type(Engineering eu, std::optional<TagType> type) {
    const double d = std::get<double>(eu.value);
    if (!type || *type == TagType::lreal || !std::isfinite(d)) return eu;
    if (*type == TagType::real) {
        const double max = std::numeric_limits<float>::max();
        if (d > max || d < -max) {
            return {Value{static_cast<float>(d < 0 ? -max : max)},
                    d < 0 ? Limit::low : Limit::high};
        }
        return {Value{static_cast<float>(d)}, eu.limit};
    }
    const double whole = std::round(d);  // half away from zero
    if (fits(whole, *type)) return {integer_value(whole, *type), eu.limit};
    return {type_end(*type, whole > 0), whole > 0 ? Limit::high : Limit::low};
}

}  // namespace

Engineering to_engineering(const Value& raw, const Scaling& scaling) {
    if (const auto* items = list_items(raw)) {
        // An array is high when any element is above the raw range, else low when any is below.
        std::vector<Value> values;
        values.reserve(items->size());
        Limit limit = Limit::none;
        for (const auto& item : *items) {
            auto eu = to_engineering(item, scaling);
            if (eu.limit == Limit::high || limit == Limit::none) limit = eu.limit;
            values.push_back(std::move(eu.value));
        }
        return {make_list(std::move(values)), limit};
    }
    const double r = to_double(raw);
    Engineering eu{Value{r * scaling.gain + scaling.offset}, Limit::none};
    if (scaling.kind != ScaleKind::gain_offset) eu = along_range(r, scaling);
    return as_eu_type(eu, scaling.eu_type);
}

std::optional<ScaleRange> eu_span(const Scaling& scaling) {
    if (scaling.kind == ScaleKind::gain_offset) return std::nullopt;
    const auto [lo, hi] = std::minmax(scaling.eu.lo, scaling.eu.hi);
    return ScaleRange{lo, hi};
}

Result<Value, RawRefusal> to_raw(double eu, const Scaling& scaling, TagType wire) {
    double raw = (eu - scaling.offset) / scaling.gain;
    if (scaling.kind != ScaleKind::gain_offset) {
        const double t = fraction(eu, scaling.eu);
        if (scaling.kind == ScaleKind::square_root && t < 0.0) return fail(RawRefusal::below_zero);
        raw = std::lerp(scaling.raw.lo, scaling.raw.hi,
                        scaling.kind == ScaleKind::square_root ? t * t : t);
    }
    if (!std::isfinite(raw)) return fail(RawRefusal::out_of_range);
    if (wire == TagType::lreal) return Value{raw};
    if (wire == TagType::real) {
        const double max = std::numeric_limits<float>::max();
        if (raw > max || raw < -max) return fail(RawRefusal::out_of_range);
        return Value{static_cast<float>(raw)};
    }
    const double whole = std::round(raw);
    if (wire == TagType::bit || !fits(whole, wire)) return fail(RawRefusal::out_of_range);
    return integer_value(whole, wire);
}

}  // namespace eip2mqtt::core::plan
