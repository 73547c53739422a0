#include "eip2mqtt/core/plan/topic_template.hpp"

#include <algorithm>

#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::core::plan {
namespace {

/// The parts of one level (`line-{line}`: literal `line-`, placeholder `line`), or a problem.
bool parse_level(std::string_view level, std::vector<std::string>& placeholders,
                 std::vector<std::string_view>& parts, std::vector<bool>& is_placeholder,
                 std::string& problem) {
    std::size_t at = 0;
    while (at < level.size()) {
        const auto open = level.find('{', at);
        const auto close = level.find('}', at);
        if (close < open) {
            problem = "has a '}' without its '{'";
            return false;
        }
        if (open > at) {
            parts.push_back(level.substr(at, std::min(open, level.size()) - at));
            is_placeholder.push_back(false);
        }
        if (open == std::string_view::npos) break;
        if (close == std::string_view::npos) {
            problem = "has a '{' without its '}'";
            return false;
        }
        const auto name = level.substr(open + 1, close - open - 1);
        if (name.empty() || name.find('{') != std::string_view::npos) {
            problem =
                name.empty() ? "has an empty placeholder '{}'" : "has a '{' inside a placeholder";
            return false;
        }
        parts.push_back(name);
        is_placeholder.push_back(true);
        if (std::find(placeholders.begin(), placeholders.end(), name) == placeholders.end()) {
            placeholders.emplace_back(name);
        }
        at = close + 1;
    }
    return true;
}

}  // namespace

std::optional<TopicTemplate> TopicTemplate::parse(std::string_view text, std::string& problem) {
    problem.clear();
    if (text.empty()) {
        problem = "is empty";
        return std::nullopt;
    }
    if (text.find_first_of("+#") != std::string_view::npos) {
        problem = "contains a wildcard ('+' or '#')";
        return std::nullopt;
    }
    if (const auto bad = text_problem(text); !bad.empty()) {
        problem = std::string(bad);
        return std::nullopt;
    }
    TopicTemplate out;
    out.text_ = std::string(text);
    std::size_t start = 0;
    for (;;) {
        const auto end = std::min(text.find('/', start), text.size());
        const auto level = text.substr(start, end - start);
        if (level.empty()) {
            problem = "has an empty level (leading, trailing or double '/')";
            return std::nullopt;
        }
        std::vector<std::string_view> parts;
        std::vector<bool> is_placeholder;
        if (!parse_level(level, out.placeholders_, parts, is_placeholder, problem)) {
            return std::nullopt;
        }
        auto& built = out.levels_.emplace_back();
        for (std::size_t i = 0; i < parts.size(); ++i) {
            built.push_back({std::string(parts[i]), is_placeholder[i]});
        }
        if (end == text.size()) break;
        start = end + 1;
    }
    const auto& names = out.placeholders_;
    if (std::find(names.begin(), names.end(), tag_placeholder) == names.end()) {
        problem = "has no {tag}: every tag of an exchange would have the same topic";
        return std::nullopt;
    }
    return out;
}

const TopicTemplate& TopicTemplate::standard() {
    static const TopicTemplate standard = [] {
        std::string problem;
        return *parse(default_topic_template, problem);
    }();
    return standard;
}

void TopicTemplate::expand_into(const Lookup& lookup, std::string& out) const {
    out.clear();
    std::string level;
    for (const auto& parts : levels_) {
        level.clear();
        for (const auto& part : parts) {
            if (part.placeholder) {
                level.append(lookup(part.text));
            } else {
                level.append(part.text);
            }
        }
        if (level.empty()) continue;
        if (!out.empty()) out.push_back('/');
        out.append(level);
    }
}

std::string TopicTemplate::expand(const Lookup& lookup) const {
    std::string out;
    expand_into(lookup, out);
    return out;
}

}  // namespace eip2mqtt::core::plan
