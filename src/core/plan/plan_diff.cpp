#include "eip2mqtt/core/plan/plan_diff.hpp"

#include <algorithm>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace eip2mqtt::core::plan {
namespace {

/// The retained topics of an exchange: its `_status`, its `_meta` and its tags'.
void collect_topics(const ExchangePlan& plan, std::unordered_set<std::string>& topics) {
    topics.insert(plan.status_topic);
    topics.insert(plan.meta_topic);
    for (const auto& tag : plan.tags) topics.insert(plan.tag_topic(tag));
}

void collect_topics(const ExchangePlan& plan, std::vector<std::string>& topics) {
    topics.push_back(plan.status_topic);
    topics.push_back(plan.meta_topic);
    for (const auto& tag : plan.tags) topics.push_back(plan.tag_topic(tag));
}

/// `label a, b, c` bounded to `max_names`, appended with "; " before it when `out` has text.
void append_part(std::string& out, std::string_view label,
                 const std::vector<std::string_view>& names, std::size_t max_names) {
    if (names.empty()) return;
    if (!out.empty()) out += "; ";
    out += label;
    for (std::size_t i = 0; i < names.size() && i < max_names; ++i) {
        out += i == 0 ? " " : ", ";
        out += names[i];
    }
    if (names.size() > max_names) {
        out += " and " + std::to_string(names.size() - max_names) + " more";
    }
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

    // Gathered in a vector, then sorted: a reload that removes a plant stops 100,000 topics,
    // and a tree of them took the loop twice as long.
    auto& stopped_topics = diff.cleared;
    for (std::size_t i = 0; i < running.size(); ++i) {
        if (kept[i]) continue;
        diff.stopped.push_back(i);
        collect_topics(*running[i], stopped_topics);
    }
    if (stopped_topics.empty()) return diff;
    std::sort(stopped_topics.begin(), stopped_topics.end());
    stopped_topics.erase(std::unique(stopped_topics.begin(), stopped_topics.end()),
                         stopped_topics.end());
    std::unordered_set<std::string> next_topics;
    for (const auto& plan : next) collect_topics(plan, next_topics);
    std::erase_if(stopped_topics,
                  [&](const std::string& topic) { return next_topics.contains(topic); });
    return diff;
}

std::string describe_diff(const PlanDiff& diff, std::span<const ExchangePlan* const> running,
                          std::span<const ExchangePlan> next, std::size_t max_names) {
    std::unordered_set<std::string_view> next_names;
    for (const auto& plan : next) next_names.insert(plan.spec.name);
    std::unordered_set<std::string_view> stopped_names;
    std::vector<std::string_view> kept;
    std::vector<std::string_view> changed;
    std::vector<std::string_view> started;
    std::vector<std::string_view> stopped;
    for (const auto index : diff.stopped) {
        const std::string_view name = running[index]->spec.name;
        stopped_names.insert(name);
        if (!next_names.contains(name)) stopped.push_back(name);
    }
    for (std::size_t i = 0; i < next.size() && i < diff.kept_from.size(); ++i) {
        const std::string_view name = next[i].spec.name;
        if (diff.kept_from[i]) {
            kept.push_back(name);
        } else {
            (stopped_names.contains(name) ? changed : started).push_back(name);
        }
    }
    std::string out;
    append_part(out, "kept", kept, max_names);
    append_part(out, "changed", changed, max_names);
    append_part(out, "started", started, max_names);
    append_part(out, "stopped", stopped, max_names);
    return out.empty() ? "nothing" : out;
}

}  // namespace eip2mqtt::core::plan
