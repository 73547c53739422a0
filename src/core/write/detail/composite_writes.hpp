#pragma once
// Writes to string and array tags: the shape of the input against the tag's; the scalar checks
// of each element are the caller's.

#include <functional>
#include <optional>

#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::write::detail {

/// The input as a number or boolean; nullopt for text, an array or an element.
std::optional<ScalarInput> as_scalar(const WriteInput& input);

/// Why a scalar tag refuses `input`, which is not a scalar: "..., got a string".
std::string not_scalar(const WriteInput& input);

/// Text for a string tag: Latin-1 characters only, at most the tag's length in bytes.
Result<plan::Value, WriteRejection> to_string_tag(const plan::TagSpec& tag,
                                                  const WriteInput& input);

using ElementCheck = std::function<Result<plan::Value, WriteRejection>(const ScalarInput&)>;

/// All elements of an array tag (a List) or one (its scalar), each through `check`.
Result<plan::Value, WriteRejection> to_array_tag(const plan::TagSpec& tag, const WriteInput& input,
                                                 const ElementCheck& check);

}  // namespace eip2mqtt::core::write::detail
