#include "core/config/detail/topic_collisions.hpp"

#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "core/config/detail/config_names.hpp"
#include "core/config/detail/topic_layout_check.hpp"

namespace eip2mqtt::core::config::detail {
namespace {

// An exchange on topic t claims t/_status, t/_values, t/_history, t/set and t/set/result; each
// of its tags t/{name}, t/{name}/set and t/{name}/set/result. Every claim is t and more levels,
// so claims of two exchanges can meet only when their topics are the same or one is an ancestor
// of the other (at any depth: t/set/result is a tag `result`'s topic under t/set,
// t/{name}/set/result one under t/{name}/set). An exchange whose topic is none of these cannot
// collide through its tags, and its tags are not claimed: 100,000 tags would otherwise cost
// 300,000 map entries. Topics refused for a reserved level (`_…`, `set`) still take part, so
// their collisions are shown too.

std::string full_topic(const std::string& base, const ExchangeConfig& exchange) {
    return base.empty() ? exchange.spec.topic : base + "/" + exchange.spec.topic;
}

/// Whether `visit(ancestor)` holds for a proper ancestor of `topic` (a/b/c: a, then a/b).
template <class Visit>
bool any_ancestor(const std::string& topic, const Visit& visit) {
    for (auto slash = topic.find('/'); slash != std::string::npos;
         slash = topic.find('/', slash + 1)) {
        if (visit(topic.substr(0, slash))) return true;
    }
    return false;
}

/// The exchanges' topics, to tell the ones whose tags may collide with another exchange's claims.
class ExchangeTopics {
public:
    explicit ExchangeTopics(const Config& config) {
        for (const auto& exchange : config.exchanges) {
            if (!topic_problem(exchange.spec.topic).empty()) continue;
            const auto topic = full_topic(config.mqtt.base_topic, exchange);
            ++uses_[topic];
            any_ancestor(topic, [&](std::string ancestor) {
                ancestors_.insert(std::move(ancestor));
                return false;
            });
        }
    }

    /// Whether another exchange's topic is `topic`, one of its ancestors or one of its
    /// descendants.
    bool nested(const std::string& topic) const {
        const auto used = uses_.find(topic);
        if ((used != uses_.end() && used->second > 1) || ancestors_.contains(topic)) return true;
        return any_ancestor(topic,
                            [&](const std::string& ancestor) { return uses_.contains(ancestor); });
    }

private:
    std::unordered_map<std::string, int> uses_;
    std::unordered_set<std::string> ancestors_;  ///< of some exchange's topic
};

/// Who claimed a topic: an exchange, or one of its tags. Described only on a collision.
struct Owner {
    const ExchangeConfig* exchange = nullptr;
    const TagConfig* tag = nullptr;  ///< null: the exchange itself
    const Mark* at = nullptr;        ///< where it was written

    std::string describe() const {
        const std::string of = "exchange " + in_quotes(exchange->spec.name);
        return tag ? "tag " + in_quotes(tag->spec.name) + " of " + of : of;
    }
    /// describe(), with its line and column: the first owner of a topic claimed twice.
    std::string describe_where() const {
        if (at == nullptr || at->line == 0) return describe();
        return describe() + " (line " + std::to_string(at->line) + ", column " +
               std::to_string(at->column) + ")";
    }
};

/// The topics claimed so far, each with its first owner; a second claim is an error.
class Claims {
public:
    explicit Claims(Diagnostics& out) : out_(out) {}

    /// Claims `topic` and each `topic`/`suffix` in turn, stopping at the first one taken.
    void claim(const std::string& topic, std::initializer_list<std::string_view> suffixes,
               Owner owner, const Mark& mark) {
        owner.at = &mark;
        std::string claimed;
        for (const auto suffix : suffixes) {
            claimed.assign(topic).append(suffix);
            const auto [it, fresh] = owners_.try_emplace(claimed, owner);
            if (!fresh) {
                out_.push_back({mark, owner.describe() + " uses topic " + in_quotes(it->first) +
                                          ", already used by " + it->second.describe_where()});
                return;
            }
        }
    }

private:
    Diagnostics& out_;
    std::unordered_map<std::string, Owner> owners_;
};

/// A tag's topic: the layout's when it has one (a template, the tag's own `topic`).
using TagTopic = std::function<void(const ExchangeConfig&, const std::string& exchange_topic,
                                    const TagConfig&, std::string&)>;

void claim_tags(Claims& claims, const ExchangeConfig& exchange, const std::string& topic,
                const TagTopic& topic_of) {
    std::unordered_set<std::string_view> seen;  // views of the tags' own names
    seen.reserve(exchange.tags.size());
    std::string tag_topic;
    for (const auto& tag : exchange.tags) {
        if (!tag_name_problem(tag.spec.name).empty()) continue;
        if (!seen.insert(tag.spec.name).second) continue;  // reported as a duplicate
        topic_of(exchange, topic, tag, tag_topic);
        const auto& at = tag.marks.contains("topic") ? tag.marks.of("topic") : tag.marks.of("name");
        claims.claim(tag_topic, {"", "/set", "/set/result"}, Owner{&exchange, &tag}, at);
    }
}

}  // namespace

void check_topic_collisions(const Config& config, const std::set<const ExchangeConfig*>& skip,
                            Diagnostics& out) {
    const ExchangeTopics topics(config);
    Claims claims(out);
    // Laid out by a template or a tag's own topic, a tag's topic may be anywhere: each is
    // claimed. Otherwise only those under nested exchange topics can meet another's (above).
    const auto tmpl = topic_template_of(config);  // nullopt: reported by check_topic_layout
    const bool anywhere = tmpl && laid_out(config);
    const plan::TopicLayout layout{tmpl ? &*tmpl : nullptr, &config.gateway.location};
    const TagTopic topic_of = [&](const ExchangeConfig& exchange, const std::string& topic,
                                  const TagConfig& tag, std::string& out) {
        if (anywhere) {
            out = plan::expand_tag_topic(layout, config.mqtt.base_topic, exchange.spec, tag.spec);
        } else {
            out.assign(topic).append("/").append(tag.spec.name);
        }
    };
    for (const auto& exchange : config.exchanges) {
        if (skip.contains(&exchange)) continue;
        if (!topic_problem(exchange.spec.topic).empty()) continue;
        const std::string topic = full_topic(config.mqtt.base_topic, exchange);
        const auto& topic_mark = exchange.marks.contains("topic") ? exchange.marks.of("topic")
                                                                  : exchange.marks.of("name");
        claims.claim(topic, {"/_status", "/_values", "/_history", "/set", "/set/result"},
                     Owner{&exchange, nullptr}, topic_mark);
        if (anywhere || topics.nested(topic)) claim_tags(claims, exchange, topic, topic_of);
    }
}

}  // namespace eip2mqtt::core::config::detail
