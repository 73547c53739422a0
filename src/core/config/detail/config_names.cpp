#include "core/config/detail/config_names.hpp"

#include <algorithm>

#include "eip2mqtt/core/config/diagnostic.hpp"
#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::core::config::detail {

std::string topic_problem(std::string_view topic) {
    if (topic.empty()) return "is empty";
    if (topic.find_first_of("+#") != std::string_view::npos) {
        return "contains a wildcard ('+' or '#')";
    }
    if (topic.front() == '/' || topic.back() == '/' || topic.find("//") != std::string_view::npos) {
        return "has an empty level (leading, trailing or double '/')";
    }
    // Control characters, NUL above all: a topic cut at a NUL would be another tag's topic.
    return std::string(plan::text_problem(topic));
}

std::string_view reserved_level(std::string_view topic, std::size_t from) {
    std::size_t start = from;
    while (start <= topic.size()) {
        const auto end = std::min(topic.find('/', start), topic.size());
        const auto level = topic.substr(start, end - start);
        if (level == "set" || (!level.empty() && level.front() == '_')) return level;
        start = end + 1;
    }
    return {};
}

std::string tag_name_problem(std::string_view name) {
    if (name.empty()) return "a tag has an empty name";
    // A loop rather than find_first_of("/+#"), which searches the set for every character:
    // this runs for every tag of the configuration.
    if (std::any_of(name.begin(), name.end(),
                    [](char c) { return c == '/' || c == '+' || c == '#'; })) {
        return "tag name " + in_quotes(name) + " contains '/', '+' or '#'";
    }
    if (const auto problem = plan::text_problem(name); !problem.empty()) {
        return "tag name " + in_quotes(name) + " " + std::string(problem);
    }
    // The gateway's own words under an exchange topic: {exchange}/set, {exchange}/_status...
    if (name == "set" || name.front() == '_') {
        return "tag name " + in_quotes(name) +
               " is reserved for the gateway's own topics ('set' and names starting with '_')";
    }
    return {};
}

}  // namespace eip2mqtt::core::config::detail
