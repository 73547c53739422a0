#pragma once
/// What a configured exchange topic or tag name must be to become part of topics: shared by the
/// validator and its topic collision check, which skips what these refuse (already reported).

#include <string>
#include <string_view>

namespace eip2mqtt::core::config::detail {

/// Why `topic` is not a valid MQTT publication topic (or a part of one), or empty when it is.
std::string topic_problem(std::string_view topic);

/// Why a tag name cannot be a topic level of its own, or empty when it can.
std::string tag_name_problem(std::string_view name);

}  // namespace eip2mqtt::core::config::detail
