#include "core/config/detail/topic_collisions.hpp"

#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "core/config/detail/config_names.hpp"

namespace eip2mqtt::core::config::detail {

void check_topic_collisions(const Config& config, const std::set<const ExchangeConfig*>& skip,
                            Diagnostics& out) {
    const std::string& base = config.mqtt.base_topic;
    // Who claimed a topic: an exchange, or one of its tags. Described only on a collision.
    struct Owner {
        const ExchangeConfig* exchange = nullptr;
        const TagConfig* tag = nullptr;  ///< null: the exchange itself

        std::string describe() const {
            const std::string of = "exchange " + in_quotes(exchange->spec.name);
            return tag ? "tag " + in_quotes(tag->spec.name) + " of " + of : of;
        }
    };
    const auto full_topic = [&](const ExchangeConfig& exchange) {
        return base.empty() ? exchange.spec.topic : base + "/" + exchange.spec.topic;
    };
    // An exchange on topic t claims t/_status, t/_values, t/_history, t/set and t/set/result; each
    // of its tags t/{name}, t/{name}/set and t/{name}/set/result. Every claim is t and more levels,
    // so claims of two exchanges can meet only when their topics are the same or one is an ancestor
    // of the other (at any depth: t/set/result is a tag `result`'s topic under t/set,
    // t/{name}/set/result one under t/{name}/set). An exchange whose topic is none of these cannot
    // collide through its tags, and its tags are not claimed: 100,000 tags would otherwise cost
    // 300,000 map entries. Topics refused for a reserved level (`_…`, `set`) still take part, so
    // their collisions are shown too.
    std::unordered_map<std::string, int> topic_uses;
    std::unordered_set<std::string> ancestors;  ///< of some exchange's topic
    for (const auto& exchange : config.exchanges) {
        if (!topic_problem(exchange.spec.topic).empty()) continue;
        const auto topic = full_topic(exchange);
        ++topic_uses[topic];
        for (auto slash = topic.find('/'); slash != std::string::npos;
             slash = topic.find('/', slash + 1)) {
            ancestors.insert(topic.substr(0, slash));
        }
    }
    const auto nested = [&](const std::string& topic) {
        if (topic_uses[topic] > 1 || ancestors.contains(topic)) return true;
        for (auto slash = topic.find('/'); slash != std::string::npos;
             slash = topic.find('/', slash + 1)) {
            if (topic_uses.contains(topic.substr(0, slash))) return true;
        }
        return false;
    };
    std::unordered_map<std::string, Owner> owners;
    const auto claim = [&](std::string topic, const Owner& owner, const Mark& mark) {
        const auto [it, fresh] = owners.try_emplace(std::move(topic), owner);
        if (!fresh) {
            out.push_back({mark, owner.describe() + " uses topic " + in_quotes(it->first) +
                                     ", already used by " + it->second.describe()});
        }
        return fresh;
    };
    for (const auto& exchange : config.exchanges) {
        if (skip.contains(&exchange)) continue;
        if (!topic_problem(exchange.spec.topic).empty()) continue;
        const std::string topic = full_topic(exchange);
        const auto& topic_mark = exchange.marks.contains("topic") ? exchange.marks.of("topic")
                                                                  : exchange.marks.of("name");
        const Owner owner{&exchange, nullptr};
        (void)(claim(topic + "/_status", owner, topic_mark) &&
               claim(topic + "/_values", owner, topic_mark) &&
               claim(topic + "/_history", owner, topic_mark) &&
               claim(topic + "/set", owner, topic_mark) &&
               claim(topic + "/set/result", owner, topic_mark));
        if (!nested(topic)) continue;
        std::unordered_set<std::string_view> seen;  // views of the tags' own names
        seen.reserve(exchange.tags.size());
        std::string tag_topic;
        for (const auto& tag : exchange.tags) {
            if (!tag_name_problem(tag.spec.name).empty()) continue;
            if (!seen.insert(tag.spec.name).second) continue;  // reported as a duplicate
            tag_topic.assign(topic).append("/").append(tag.spec.name);
            const Owner tag_owner{&exchange, &tag};
            (void)(claim(tag_topic, tag_owner, tag.marks.of("name")) &&
                   claim(tag_topic + "/set", tag_owner, tag.marks.of("name")) &&
                   claim(tag_topic + "/set/result", tag_owner, tag.marks.of("name")));
        }
    }
}

}  // namespace eip2mqtt::core::config::detail
