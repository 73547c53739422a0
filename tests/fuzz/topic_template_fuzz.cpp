// Fuzzes mqtt.topic_template: any text is parsed; a template that parses names {tag}, and
// expands to a topic a broker accepts with no empty level, whether its placeholders stand for a
// level of text or for nothing (the levels left out).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "eip2mqtt/core/plan/topic_rules.hpp"
#include "eip2mqtt/core/plan/topic_template.hpp"

namespace {

using namespace eip2mqtt::core;

bool has_empty_level(std::string_view topic) {
    return !topic.empty() &&
           (topic.front() == '/' || topic.back() == '/' || topic.find("//") != std::string::npos);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    std::string problem;
    const auto parsed = plan::TopicTemplate::parse(text, problem);
    if (!parsed) {
        if (problem.empty()) std::abort();  // a refusal always says why
        return 0;
    }
    const auto& names = parsed->placeholders();
    if (std::find(names.begin(), names.end(), plan::tag_placeholder) == names.end()) std::abort();
    const auto full = parsed->expand([](std::string_view) { return std::string_view("v"); });
    if (!plan::topic_name_problem(full).empty() || has_empty_level(full)) std::abort();
    const auto bare = parsed->expand([](std::string_view name) {
        return name == plan::tag_placeholder ? std::string_view("v") : std::string_view();
    });
    if (bare.empty() || has_empty_level(bare)) std::abort();
    return 0;
}
