#pragma once
/// The checks of a tag's engineering values (docs/configuration.md "Engineering values"): a
/// scale that can be computed and inverted, a percent deadband with a span to take it of, and
/// `min`/`max` inside the engineering range.
///
/// Module-private to src/core/config.

#include <functional>
#include <string>

#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::core::config::detail {

/// A limit or a range end as messages write it: `4000`, `0.5`, `-40` (six decimals at most).
std::string number_text(double value);

/// Adds the problems of `tag`'s scale and percent deadband to `out`; `what` names the tag.
void check_engineering(const TagConfig& tag, const std::function<std::string()>& what,
                       Diagnostics& out);

/// Whether `value` (a min or a max of a scaled tag) lies outside its scale's engineering
/// range: the message's tail (" is outside the engineering range 0..100"), empty when inside or
/// when the scale has no range.
std::string outside_eu_range(const plan::Scaling& scale, double value);

}  // namespace eip2mqtt::core::config::detail
