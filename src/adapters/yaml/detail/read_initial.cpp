#include "adapters/yaml/detail/read_initial.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "adapters/yaml/detail/read_engineering.hpp"
#include "adapters/yaml/detail/scalar_text.hpp"
#include "eip2mqtt/core/plan/latin1.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

using core::plan::TagType;

/// `initial` as the tag's type holds it. Out-of-range values are kept (as int64 or double)
/// for validate() to report against the type's range.
std::optional<core::plan::Value> read_scalar(Reader& reader, const Node& value, TagType type,
                                             const Mark& at) {
    const std::string_view text = value.scalar();
    switch (type) {
        case TagType::bit: {
            if (text == "0") return core::plan::Value{false};
            if (text == "1") return core::plan::Value{true};
            if (const auto b = reader.boolean(value, "initial", at)) return core::plan::Value{*b};
            return std::nullopt;
        }
        case TagType::real:
        case TagType::lreal: {
            const auto d = reader.number(value, "initial", at);
            if (!d) return std::nullopt;
            if (type == TagType::real && std::fabs(*d) <= std::numeric_limits<float>::max()) {
                return core::plan::Value{static_cast<float>(*d)};
            }
            return core::plan::Value{*d};
        }
        default: {
            if (const auto n = parse_integer<std::int64_t>(text)) {
                if (core::plan::type_min(type) >= 0 && *n >= 0) {
                    return core::plan::Value{static_cast<std::uint64_t>(*n)};
                }
                return core::plan::Value{*n};
            }
            if (const auto n = parse_integer<std::uint64_t>(text)) {
                return core::plan::Value{*n};
            }
            reader.error(at, "expected an integer for 'initial'");
            return std::nullopt;
        }
    }
}

/// One value of the tag's type: in engineering units when it is scaled.
std::optional<core::plan::Value> read_one(Reader& reader, const Node& value,
                                          const core::plan::TagSpec& tag, const Mark& at) {
    const auto& scale = tag.scale();
    return scale ? read_initial_eu(reader, value, *scale, tag.type, at)
                 : read_scalar(reader, value, tag.type, at);
}

std::optional<core::plan::Value> read_text(Reader& reader, const Node& value,
                                           const core::plan::TagSpec& tag, const Mark& at) {
    const std::string text(value.scalar());
    const auto latin1 = core::plan::utf8_to_latin1(text);
    if (!value.is_scalar() || !latin1) {
        reader.error(at, "expected a text of Latin-1 characters for 'initial'");
        return std::nullopt;
    }
    if (latin1->size() > tag.count) {
        reader.error(at, "'initial' is " + std::to_string(latin1->size()) +
                             " bytes, longer than the string's length " +
                             std::to_string(tag.count));
        return std::nullopt;
    }
    return core::plan::make_text(text);
}

}  // namespace

std::optional<core::plan::Value> read_tag_initial(Reader& reader, const Node& value,
                                                  const core::plan::TagSpec& tag, const Mark& at) {
    if (tag.type == TagType::string) return read_text(reader, value, tag, at);
    if (!tag.is_array()) return read_one(reader, value, tag, at);
    // An array takes one value for every element, or a sequence of exactly `count`.
    std::vector<core::plan::Value> items;
    if (!value.is_sequence()) {
        auto one = read_one(reader, value, tag, at);
        if (!one) return std::nullopt;
        items.assign(tag.count, *one);
        return core::plan::make_list(std::move(items));
    }
    if (value.size() != tag.count) {
        reader.error(at, "'initial' has " + std::to_string(value.size()) +
                             " values for an array of " + std::to_string(tag.count));
        return std::nullopt;
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
        auto item = read_one(reader, value.item(i), tag, at);
        if (!item) return std::nullopt;
        items.push_back(std::move(*item));
    }
    return core::plan::make_list(std::move(items));
}

}  // namespace eip2mqtt::adapters::yaml::detail
