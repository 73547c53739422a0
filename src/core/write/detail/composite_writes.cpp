#include "core/write/detail/composite_writes.hpp"

#include <string>
#include <utility>
#include <vector>

#include "eip2mqtt/core/plan/latin1.hpp"

namespace eip2mqtt::core::write::detail {
namespace {

WriteRejection reject(WriteError error, std::string message) { return {error, std::move(message)}; }

std::string array_shape(const plan::TagSpec& tag) {
    return "expected an array of " + std::to_string(tag.count) +
           R"( values or {"index": i, "value": v})";
}

}  // namespace

std::optional<ScalarInput> as_scalar(const WriteInput& input) {
    return std::visit(
        [](const auto& v) -> std::optional<ScalarInput> {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_constructible_v<ScalarInput, V>) {
                return ScalarInput{v};
            } else {
                return std::nullopt;
            }
        },
        input);
}

std::string not_scalar(const WriteInput& input) {
    const char* const got = std::holds_alternative<std::string>(input)  ? "a string"
                            : std::holds_alternative<ArrayInput>(input) ? "an array"
                                                                        : "an array element";
    return std::string("expected a number or true/false, got ") + got;
}

Result<plan::Value, WriteRejection> to_string_tag(const plan::TagSpec& tag,
                                                  const WriteInput& input) {
    const auto* text = std::get_if<std::string>(&input);
    if (text == nullptr) return fail(reject(WriteError::wrong_type, "expected a string"));
    const auto latin1 = plan::utf8_to_latin1(*text);
    if (!latin1) {
        return fail(reject(WriteError::wrong_type, "has a character with no Latin-1 form"));
    }
    if (latin1->size() > tag.count) {
        return fail(reject(WriteError::out_of_range,
                           "longer than the tag's " + std::to_string(tag.count) + " bytes"));
    }
    return plan::make_text(*text);
}

Result<plan::Value, WriteRejection> to_array_tag(const plan::TagSpec& tag, const WriteInput& input,
                                                 const ElementCheck& check) {
    if (const auto* element = std::get_if<ElementInput>(&input)) {
        if (element->index >= tag.count) {
            return fail(reject(WriteError::out_of_range,
                               "index " + std::to_string(element->index) + " beyond the " +
                                   std::to_string(tag.count) + " elements"));
        }
        return check(element->value);
    }
    const auto* array = std::get_if<ArrayInput>(&input);
    if (array == nullptr || array->items.size() != tag.count) {
        return fail(reject(WriteError::wrong_type, array_shape(tag)));
    }
    std::vector<plan::Value> items;
    items.reserve(array->items.size());
    for (std::size_t i = 0; i < array->items.size(); ++i) {
        auto item = check(array->items[i]);
        if (!item) {
            auto rejection = item.error();
            rejection.message = "element " + std::to_string(i) + ": " + rejection.message;
            return fail(std::move(rejection));
        }
        items.push_back(std::move(item).value());
    }
    return plan::make_list(std::move(items));
}

}  // namespace eip2mqtt::core::write::detail
