#pragma once
/// Topics laid out by asset (docs/configuration.md, "Topics and payloads"): mqtt.topic_template,
/// the `location` mappings of the gateway, the exchanges and the tags, and the tags' own
/// `topic_name` and `topic`, checked as written and as each tag's topic expands.

#include <optional>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/diagnostic.hpp"
#include "eip2mqtt/core/plan/topic_template.hpp"

namespace eip2mqtt::core::config::detail {

/// The configuration's template; nullopt when it does not parse (check_topic_layout says why).
std::optional<plan::TopicTemplate> topic_template_of(const Config& config);

/// Whether any tag's topic may be other than {base}/{exchange topic}/{name}.
bool laid_out(const Config& config);

/// Appends every problem of the layout to `out`: a template that does not parse or names a
/// placeholder no location has, location keys and values that cannot be topic levels, and each
/// tag topic a broker would refuse or that takes a level the gateway keeps for itself.
void check_topic_layout(const Config& config, Diagnostics& out);

}  // namespace eip2mqtt::core::config::detail
