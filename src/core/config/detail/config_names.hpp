#pragma once
/// What a configured exchange topic or tag name must be to become part of topics: shared by the
/// validator and its topic collision check, which skips what these refuse (already reported).

#include <cstddef>
#include <string>
#include <string_view>

namespace eip2mqtt::core::config::detail {

/// Why `topic` is not a valid MQTT publication topic (or a part of one), or empty when it is.
std::string topic_problem(std::string_view topic);

/// The first level of `topic`, from byte `from` on, that the gateway keeps for its own topics
/// (`set`, or one starting with `_`); empty when none is.
std::string_view reserved_level(std::string_view topic, std::size_t from = 0);

/// Why a tag name cannot be a topic level of its own, or empty when it can.
std::string tag_name_problem(std::string_view name);

}  // namespace eip2mqtt::core::config::detail
