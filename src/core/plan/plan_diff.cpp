#include "eip2mqtt/core/plan/plan_diff.hpp"

#include <set>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

namespace eip2mqtt::core::plan {
namespace {

/// The retained topics of an exchange: its `_status` and its tags'.
template <class Topics>
void collect_topics(const ExchangePlan& plan, Topics& topics) {
    topics.insert(plan.status_topic);
    for (const auto& tag : plan.tags) topics.insert(plan.tag_topic(tag));
}

}  // namespace

PlanDiff diff_plans(std::span<const ExchangePlan* const> running,
                    std::span<const ExchangePlan> next) {
    std::unordered_map<std::string_view, std::size_t> by_name;
    for (std::size_t i = 0; i < running.size(); ++i) by_name.emplace(running[i]->spec.name, i);

    PlanDiff diff;
    diff.kept_from.reserve(next.size());
    std::vector<bool> kept(running.size(), false);
    for (const auto& plan : next) {
        const auto it = by_name.find(plan.spec.name);
        if (it == by_name.end() || !(*running[it->second] == plan)) {
            diff.kept_from.push_back(std::nullopt);
            continue;
        }
        diff.kept_from.push_back(it->second);
        kept[it->second] = true;
    }

    std::set<std::string> stopped_topics;
    for (std::size_t i = 0; i < running.size(); ++i) {
        if (kept[i]) continue;
        diff.stopped.push_back(i);
        collect_topics(*running[i], stopped_topics);
    }
    if (stopped_topics.empty()) return diff;
    std::unordered_set<std::string> next_topics;
    for (const auto& plan : next) collect_topics(plan, next_topics);
    for (auto& topic : stopped_topics) {
        if (!next_topics.contains(topic)) diff.cleared.push_back(topic);
    }
    return diff;
}

}  // namespace eip2mqtt::core::plan
