#include "eip2mqtt/core/plan/tag_type.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "core/detail/lower.hpp"
#include "eip2mqtt/core/edit_distance.hpp"

namespace eip2mqtt::core::plan {
namespace {

using detail::lower;

/// Whether `text` is `lower_case` in any case (std::tolower, as lower()).
bool equals_lower(std::string_view text, std::string_view lower_case) {
    return std::equal(text.begin(), text.end(), lower_case.begin(), lower_case.end(),
                      [](unsigned char a, char b) { return std::tolower(a) == b; });
}

constexpr std::array<std::pair<std::string_view, TagType>, 15> yaml_names{{
    {"bit", TagType::bit},
    {"bool", TagType::bit},
    {"byte", TagType::byte},
    {"usint", TagType::byte},
    {"int", TagType::int_},
    {"word", TagType::word},
    {"uint", TagType::word},
    {"dint", TagType::dint},
    {"udint", TagType::udint},
    {"dword", TagType::udint},
    {"real", TagType::real},
    {"lint", TagType::lint},
    {"long", TagType::lint},
    {"lreal", TagType::lreal},
    {"string", TagType::string},
}};

/// Names other languages and vendors give the §3 types, all lower case.
constexpr std::array<std::pair<std::string_view, std::string_view>, 18> foreign_names{{
    {"float", "real"},
    {"float32", "real"},
    {"single", "real"},
    {"double", "lreal"},
    {"float64", "lreal"},
    {"boolean", "bit"},
    {"int16", "int"},
    {"short", "int"},
    {"uint16", "word"},
    {"ushort", "word"},
    {"int32", "dint"},
    {"integer", "dint"},
    {"uint32", "udint"},
    {"int64", "lint"},
    {"longlong", "lint"},
    {"uint8", "byte"},
    {"text", "string"},
    {"char", "string"},
}};

}  // namespace

std::optional<std::string_view> tag_type_hint(std::string_view unknown) {
    const std::string key = lower(unknown);
    for (const auto& [foreign, ours] : foreign_names) {
        if (foreign == key) return ours;
    }
    // One edit from a name of at least 4 letters: `reel`, `dintt`; a 3-letter name is one edit
    // from too many others to guess.
    for (const auto& [text, type] : yaml_names) {
        if (text.size() >= 4 && core::edit_distance(key, text) == 1) return text;
    }
    return std::nullopt;
}

std::optional<TagType> parse_tag_type(std::string_view name, TypeNaming naming) {
    // Compared in place, not through lower(): this runs once for every tag of a point list.
    // docs/protocol.md §6: point lists say Word for a signed 16-bit value.
    if (naming == TypeNaming::point_list && equals_lower(name, "word")) return TagType::int_;
    for (const auto& [text, type] : yaml_names) {
        if (equals_lower(name, text)) return type;
    }
    return std::nullopt;
}

std::size_t size_of(TagType type) {
    switch (type) {
        case TagType::bit:
        case TagType::byte:
        case TagType::string:
            return 1;
        case TagType::int_:
        case TagType::word:
            return 2;
        case TagType::dint:
        case TagType::udint:
        case TagType::real:
            return 4;
        case TagType::lint:
        case TagType::lreal:
            return 8;
    }
    return 1;
}

bool is_integer(TagType type) {
    return type != TagType::bit && type != TagType::real && type != TagType::lreal &&
           type != TagType::string;
}

double type_min(TagType type) {
    switch (type) {
        case TagType::bit:
        case TagType::byte:
        case TagType::word:
        case TagType::udint:
        case TagType::string:
            return 0.0;
        case TagType::int_:
            return std::numeric_limits<std::int16_t>::min();
        case TagType::dint:
            return std::numeric_limits<std::int32_t>::min();
        case TagType::lint:
            return static_cast<double>(std::numeric_limits<std::int64_t>::min());
        case TagType::real:
            return -std::numeric_limits<float>::max();
        case TagType::lreal:
            return -std::numeric_limits<double>::max();
    }
    return 0.0;
}

double type_max(TagType type) {
    switch (type) {
        case TagType::bit:
            return 1.0;
        case TagType::string:
            return 0.0;
        case TagType::byte:
            return std::numeric_limits<std::uint8_t>::max();
        case TagType::int_:
            return std::numeric_limits<std::int16_t>::max();
        case TagType::word:
            return std::numeric_limits<std::uint16_t>::max();
        case TagType::dint:
            return std::numeric_limits<std::int32_t>::max();
        case TagType::udint:
            return std::numeric_limits<std::uint32_t>::max();
        case TagType::lint:
            return static_cast<double>(std::numeric_limits<std::int64_t>::max());
        case TagType::real:
            return std::numeric_limits<float>::max();
        case TagType::lreal:
            return std::numeric_limits<double>::max();
    }
    return 0.0;
}

}  // namespace eip2mqtt::core::plan
