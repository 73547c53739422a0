#include "core/config/detail/redundancy_check.hpp"

#include <string>
#include <string_view>

#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::core::config::detail {

void check_redundancy(const Config& config, Diagnostics& out) {
    const auto& redundancy = config.redundancy;
    if (!redundancy.enabled()) return;
    const auto& at = redundancy.marks.of("pair");
    const std::string named = "redundancy pair " + in_quotes(redundancy.pair) + " ";
    if (redundancy.pair.find_first_of("/+#") != std::string::npos) {
        out.push_back({at, named + "contains '/', '+' or '#' (it is a topic level)"});
        return;
    }
    if (const auto problem = plan::text_problem(redundancy.pair); !problem.empty()) {
        out.push_back({at, named + std::string(problem) + " (it is a topic level)"});
        return;
    }
    constexpr std::string_view pair_level = "/_gateway/_pair/";
    constexpr std::string_view leader_level = "/leader";
    const auto bytes = config.mqtt.base_topic.size() + pair_level.size() + redundancy.pair.size() +
                       leader_level.size();
    if (bytes > plan::max_topic_bytes) {
        out.push_back({at, named + "makes topic '{base_topic}/_gateway/_pair/{pair}/leader' " +
                               std::to_string(bytes) + " bytes long (MQTT allows " +
                               std::to_string(plan::max_topic_bytes) + ")"});
    }
}

}  // namespace eip2mqtt::core::config::detail
