#pragma once
/// How one more MQTT connection lays out the exchanges' topics (docs/configuration.md, "Several
/// brokers at once"): plans hold their topics once, under the first connection's base_topic; a
/// connection with a base_topic of its own says them under it. A topic that is the first base,
/// or starts with it and then '/', has that part swapped on the way out, and back on the way in
/// (a write's topic, its response topic). Others (a tag's own `topic`) are the same on every
/// connection.

#include <string>
#include <string_view>

namespace eip2mqtt::core::plan {

class TopicRebase {
public:
    TopicRebase() = default;
    TopicRebase(std::string first_base, std::string own_base)
        : first_(std::move(first_base)), own_(std::move(own_base)) {}

    /// Nothing to swap: the two bases are one.
    bool identity() const { return first_ == own_; }
    /// A topic (or a filter) as the connection says it, in place.
    void outward(std::string& topic) const { swap(topic, first_, own_); }
    /// A topic the connection heard, as the plans know it, in place.
    void inward(std::string& topic) const { swap(topic, own_, first_); }

private:
    static void swap(std::string& topic, std::string_view from, std::string_view to) {
        if (from == to || !topic.starts_with(from)) return;
        if (topic.size() != from.size() && topic[from.size()] != '/') return;
        topic.replace(0, from.size(), to);
    }

    std::string first_;
    std::string own_;
};

}  // namespace eip2mqtt::core::plan
