#pragma once
/// How far apart two words are, for "did you mean" suggestions (configuration keys, type
/// names): the Levenshtein distance, counting each inserted, removed or replaced character.

#include <cstddef>
#include <string_view>

namespace eip2mqtt::core {

std::size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace eip2mqtt::core
