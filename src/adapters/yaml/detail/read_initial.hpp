#pragma once
/// A tag's `initial`: the value a produced exchange starts from, read as the tag holds it (a
/// number in its type or in engineering units, a sequence for an array, a text for a string).
///
/// Module-private to src/adapters/yaml.

#include <optional>

#include "adapters/yaml/detail/reader.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// The tag's initial value; nullopt, with the error reported, when it does not read.
/// Out-of-range numbers are kept (as int64 or double) for the core's checks to report.
std::optional<core::plan::Value> read_tag_initial(Reader& reader, const Node& value,
                                                  const core::plan::TagSpec& tag, const Mark& at);

}  // namespace eip2mqtt::adapters::yaml::detail
