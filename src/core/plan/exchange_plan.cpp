#include "eip2mqtt/core/plan/exchange_plan.hpp"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <utility>

#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::core::plan {
namespace {

std::string join(const std::string& base, const std::string& level) {
    if (base.empty()) return level;
    if (level.empty()) return base;
    return base + "/" + level;
}

}  // namespace

std::uint16_t resolved_length(const ExchangeSpec& spec) {
    if (spec.length) return *spec.length;
    std::size_t end = 0;
    for (const auto& tag : spec.tags) {
        end = std::max(end, std::size_t{tag.address.byte} + tag_size(tag));
    }
    return static_cast<std::uint16_t>(
        std::min<std::size_t>(end, std::numeric_limits<std::uint16_t>::max()));
}

ExchangePlan make_exchange_plan(ExchangeSpec spec, const std::string& base_topic,
                                const ExchangeDefaults& defaults) {
    ExchangePlan plan;
    plan.length = resolved_length(spec);
    if (spec.direction == Direction::consume) {
        // docs/protocol.md §4 rule 8: default 3 x the expected period; 0 disables.
        plan.timeout = spec.timeout.value_or(3 * spec.period);
        plan.timestamp = spec.timestamp.value_or(defaults.timestamp);
        plan.clock_tolerance = spec.clock_tolerance.value_or(defaults.clock_tolerance);
    }
    plan.topic = join(base_topic, spec.topic);
    plan.status_topic = plan.topic + "/_status";
    plan.values_topic = plan.topic + "/_values";
    plan.meta_topic = plan.topic + "/_meta";
    plan.set_topic = plan.topic + "/set";
    plan.tags.reserve(spec.tags.size());
    for (const auto& tag : spec.tags) plan.tags.push_back({tag});
    plan.spec = std::move(spec);
    return plan;
}

std::string ExchangePlan::tag_topic(const TagPlan& tag) const {
    std::string out;
    out.reserve(topic.size() + 1 + tag.spec.name.size());
    tag_topic_into(tag, out);
    return out;
}

void ExchangePlan::tag_topic_into(const TagPlan& tag, std::string& out) const {
    out.assign(topic).append("/").append(tag.spec.name);
}

}  // namespace eip2mqtt::core::plan
