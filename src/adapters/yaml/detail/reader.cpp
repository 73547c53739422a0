// The scalar readers that are no templates.

#include "adapters/yaml/detail/reader.hpp"

namespace eip2mqtt::adapters::yaml::detail {

std::optional<std::string> Reader::text(const Node& value, const std::string& key, const Mark& at) {
    if (value.is_null()) return std::string();
    if (!value.is_scalar()) {
        error(at, "expected a string for " + in_quotes(key));
        return std::nullopt;
    }
    return std::string(value.scalar());
}

std::optional<core::plan::TimestampSource> Reader::timestamp_source(const Node& value,
                                                                    const std::string& key,
                                                                    const Mark& at) {
    return parsed(value, key, at, core::plan::parse_timestamp_source,
                  "is not one of auto, producer, receive");
}

std::optional<bool> Reader::boolean(const Node& value, const std::string& key, const Mark& at) {
    if (value.is_scalar()) {
        const auto word = lower(value.scalar());
        if (word == "true" || word == "yes" || word == "on") return true;
        if (word == "false" || word == "no" || word == "off") return false;
    }
    error(at, "expected true or false for " + in_quotes(key));
    return std::nullopt;
}

}  // namespace eip2mqtt::adapters::yaml::detail
