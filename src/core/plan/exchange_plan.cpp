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

/// Whether `tag`'s topic may differ from {exchange topic}/{name}.
bool own_topic(const TopicLayout& layout, const TagSpec& tag) {
    const bool standard = layout.topic_template == nullptr || layout.topic_template->is_standard();
    return !standard || !tag.topic().empty() || !tag.topic_name().empty();
}

/// ExchangePlan::tag_topics: left empty while every topic is the default one.
void fill_tag_topics(ExchangePlan& plan, const ExchangeSpec& spec, const std::string& base_topic,
                     const TopicLayout& layout) {
    const auto standard = [&](const TagSpec& tag) { return plan.topic + "/" + tag.name; };
    for (std::size_t i = 0; i < spec.tags.size(); ++i) {
        const auto& tag = spec.tags[i];
        if (plan.tag_topics.empty() && !own_topic(layout, tag)) continue;
        auto topic = own_topic(layout, tag) ? expand_tag_topic(layout, base_topic, spec, tag)
                                            : standard(tag);
        if (plan.tag_topics.empty()) {
            if (topic == standard(tag)) continue;
            plan.tag_topics.reserve(spec.tags.size());
            for (std::size_t j = 0; j < i; ++j) plan.tag_topics.push_back(standard(spec.tags[j]));
        }
        plan.tag_topics.push_back(std::move(topic));
    }
}

}  // namespace

std::string expand_tag_topic(const TopicLayout& layout, const std::string& base_topic,
                             const ExchangeSpec& spec, const TagSpec& tag) {
    if (!tag.topic().empty()) return tag.topic();
    const auto& tmpl = layout.topic_template ? *layout.topic_template : TopicTemplate::standard();
    return tmpl.expand([&](std::string_view name) -> std::string_view {
        if (name == base_placeholder) return base_topic;
        if (name == exchange_placeholder) return spec.topic;
        if (name == tag_placeholder) return tag.topic_name().empty() ? tag.name : tag.topic_name();
        if (const auto* value = tag.location().find(name)) return *value;
        if (const auto* value = spec.location.find(name)) return *value;
        if (layout.gateway_location) {
            if (const auto* value = layout.gateway_location->find(name)) return *value;
        }
        return {};
    });
}

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
                                const ExchangeDefaults& defaults, const TopicLayout& layout) {
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
    fill_tag_topics(plan, spec, base_topic, layout);
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
    if (!tag_topics.empty()) {
        out.assign(tag_topics[static_cast<std::size_t>(&tag - tags.data())]);
        return;
    }
    out.assign(topic).append("/").append(tag.spec.name);
}

}  // namespace eip2mqtt::core::plan
