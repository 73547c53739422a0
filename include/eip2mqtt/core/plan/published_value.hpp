#pragma once
/// What a tag publishes of the raw value an exchange carries: the engineering value of a
/// scaled tag, the wire's value of any other. Samples travel raw (journals and a pair's window
/// keep the wire's value); each northbound makes them published values here, as it formats.

#include "eip2mqtt/core/plan/scaling.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"

namespace eip2mqtt::core::plan {

/// The published value of `raw`, with the raw range's limit it passed (none unless scaled).
inline Engineering published_value(const TagSpec& tag, const Value& raw) {
    const auto& scale = tag.scale();
    return scale ? to_engineering(raw, *scale) : Engineering{raw, Limit::none};
}

/// The type of what the tag publishes: the wire type, or a scaled tag's `type_eu` (lreal, a
/// double, when it names none).
inline TagType published_type(const TagSpec& tag) {
    const auto& scale = tag.scale();
    if (!scale) return tag.type;
    return scale->eu_type.value_or(TagType::lreal);
}

}  // namespace eip2mqtt::core::plan
