// docs/mqtt-api.md "Writes": a message on a `…/set` topic is checked whole (response topic, tag,
// retained, payload, type, range) before anything is staged, and one bad value refuses a
// multi-tag write.

#include "eip2mqtt/app/northbound/json_tree/write_router.hpp"

#include <algorithm>
#include <set>
#include <string_view>
#include <vector>

#include "eip2mqtt/app/northbound/json_tree/write_payload.hpp"
#include "eip2mqtt/core/plan/topic_rules.hpp"

namespace eip2mqtt::app::northbound::json_tree {
namespace {

using core::write::WriteError;
using core::write::WriteRejection;

constexpr std::string_view set_suffix = "/set";
constexpr std::string_view result_suffix = "/result";

/// Whether `topic` has a level `set` with at least one level after it: the gateway publishes
/// nothing there but write results, since tag names and exchange topic levels cannot be `set`.
bool below_a_set_level(std::string_view topic) {
    std::size_t start = 0;
    for (;;) {
        const auto end = topic.find('/', start);
        if (end == std::string_view::npos) return false;
        if (topic.substr(start, end - start) == "set") return true;
        start = end + 1;
    }
}

std::optional<std::size_t> find_tag(const core::plan::ExchangePlan& plan, std::string_view name) {
    const auto& tags = plan.tags;
    const auto tag =
        std::find_if(tags.begin(), tags.end(), [&](const auto& t) { return t.spec.name == name; });
    if (tag == tags.end()) return std::nullopt;
    return static_cast<std::size_t>(tag - tags.begin());
}

/// The validated writes of `payload`: one tag's (`tag_index`) or, without one, the exchange's
/// multi-tag object. The first bad value refuses the whole message.
std::optional<WriteRejection> collect_writes(const core::plan::ExchangePlan& plan,
                                             std::optional<std::size_t> tag_index,
                                             const std::string& payload,
                                             core::config::PayloadFormat profile,
                                             std::vector<core::write::TagWrite>& writes) {
    // One tag's input against its spec; a multi-tag write's messages name the tag.
    const auto add = [&](std::size_t index,
                         const core::write::WriteInput& input) -> std::optional<WriteRejection> {
        const auto& tag = plan.tags[index].spec;
        auto value = core::write::validate_write(tag, input);
        if (!value) {
            auto rejection = value.error();
            if (!tag_index) rejection.message = tag.name + ": " + rejection.message;
            return rejection;
        }
        writes.push_back({index, std::move(value).value(), core::write::element_of(input)});
        return std::nullopt;
    };
    if (tag_index) {
        const auto input = parse_tag_write(payload, profile);
        if (!input) return WriteRejection{input.error().error, input.error().message};
        return add(*tag_index, input.value());
    }
    const auto inputs = parse_exchange_write(payload, profile);
    if (!inputs) return WriteRejection{inputs.error().error, inputs.error().message};
    for (const auto& entry : inputs.value()) {
        // Not a structured binding: clang 14 (the fuzz build) cannot capture one.
        const auto& name = entry.first;
        auto index = find_tag(plan, name);
        // Kepware names a tag `{exchange}.{tag}`.
        const auto& exchange = plan.spec.name;
        if (!index && name.size() > exchange.size() && name.starts_with(exchange) &&
            name[exchange.size()] == '.') {
            index = find_tag(plan, std::string_view(name).substr(exchange.size() + 1));
        }
        if (!index) {
            return WriteRejection{WriteError::unknown_tag,
                                  "unknown tag " + name + " in exchange " + plan.spec.name};
        }
        if (auto rejection = add(*index, entry.second)) return rejection;
    }
    return std::nullopt;
}

}  // namespace

WriteRouter::WriteRouter(WriteRouterOptions options) : options_(std::move(options)) {}

void WriteRouter::clear() {
    exchanges_.clear();
    tags_.clear();
}

void WriteRouter::add(const core::plan::ExchangePlan& plan) {
    const auto& route = exchanges_[plan.topic] = Route{&plan};
    for (std::size_t i = 0; i < plan.tag_topics.size(); ++i) {
        tags_[plan.tag_topics[i]] = TagRoute{&route, i};
    }
}

std::vector<std::string> WriteRouter::exact_subscriptions() const {
    std::vector<std::string> filters;
    for (const auto& [topic, route] : exchanges_) {
        filters.push_back(topic + std::string(set_suffix));
        const auto& plan = *route.plan;
        if (plan.spec.direction != core::plan::Direction::produce) continue;
        for (const auto& tag : plan.tags) filters.push_back(plan.tag_topic(tag) + "/set");
    }
    std::sort(filters.begin(), filters.end());
    return filters;
}

std::vector<std::string> WriteRouter::subscriptions() const {
    if (!tags_.empty()) return exact_subscriptions();
    // None of our own publications match these filters, since tag names cannot be `set`.
    const auto& base = options_.base_topic;
    const auto base_levels = std::count(base.begin(), base.end(), '/') + 1;
    std::set<long> depths;
    for (const auto& [topic, route] : exchanges_) {
        const long levels = std::count(topic.begin(), topic.end(), '/') + 1 - base_levels;
        depths.insert(levels + 1);                                 // {exchange topic}/set
        if (!route.plan->tags.empty()) depths.insert(levels + 2);  // {exchange topic}/{tag}/set
    }
    std::vector<std::string> filters;
    for (const auto depth : depths) {
        std::string filter = base;
        for (long i = 1; i < depth; ++i) filter += "/+";
        filters.push_back(filter + "/set");
    }
    return filters;
}

std::string WriteRouter::response_topic_problem(const std::string& topic) const {
    if (auto problem = core::plan::topic_name_problem(topic); !problem.empty()) return problem;
    // A client allowed to write only `…/set` must not make the gateway publish `{"ok":true}`
    // on a tag's topic or on `_gateway/…/state`, in the gateway's name.
    const auto& base = options_.base_topic;
    const bool under_base =
        topic == base ||
        (topic.starts_with(base) && topic.size() > base.size() && topic[base.size()] == '/');
    // A tag laid out by a template may be outside the base topic: never answered on either.
    if (tags_.contains(topic)) return "is a tag's topic";
    if (under_base && !options_.allow_response_topics_under_base &&
        !below_a_set_level(std::string_view(topic).substr(base.size()))) {
        return "lies under the base topic " + base +
               " outside a set topic (mqtt.allow_response_topics_under_base is false)";
    }
    return {};
}

std::optional<WriteRouter::Target> WriteRouter::find_target(std::string_view stem) const {
    const std::string key(stem);
    if (const auto it = exchanges_.find(key); it != exchanges_.end()) {
        return Target{&it->second, std::nullopt, {}};
    }
    if (const auto it = tags_.find(key); it != tags_.end()) {
        return Target{it->second.route, it->second.tag_index, {}};
    }
    // `{exchange topic}/{name}/set`: tag names hold no '/', so the exchange topic is what comes
    // before the last level, and the tag is found by its name in that exchange.
    const auto slash = stem.rfind('/');
    if (slash == std::string_view::npos) return std::nullopt;
    const auto exchange = exchanges_.find(std::string(stem.substr(0, slash)));
    // An exchange whose tags have topics of their own is not written by tag name.
    if (exchange == exchanges_.end() || !exchange->second.plan->tag_topics.empty()) {
        return std::nullopt;
    }
    const auto name = stem.substr(slash + 1);
    Target target{&exchange->second, find_tag(*exchange->second.plan, name), {}};
    if (!target.tag_index) target.unknown_tag = std::string(name);
    return target;
}

std::optional<WriteDecision> WriteRouter::route(const adapters::mqtt::Incoming& message) const {
    const std::string_view topic = message.topic;
    if (!topic.ends_with(set_suffix)) return std::nullopt;
    // An empty message is how a retained one is cleared (`mosquitto_pub -r -n -t …/set`): the
    // broker passes the clearing on to subscribers. It asks for nothing, so nothing answers it.
    if (message.payload.empty()) return std::nullopt;
    const auto target = find_target(topic.substr(0, topic.size() - set_suffix.size()));
    if (!target) return std::nullopt;
    const auto& route = *target->route;
    const auto& plan = *route.plan;

    WriteDecision decision;
    decision.reply.correlation_data = message.correlation_data;
    decision.reply.topic = message.topic;
    decision.reply.topic += result_suffix;
    // A conforming broker delivers only valid topics, but `{topic}/result` can still pass the
    // limit for an unknown tag with a name near 65,535 bytes: such a write has nowhere to be
    // answered (an empty reply topic) unless it names a good response topic.
    if (!core::plan::topic_name_problem(decision.reply.topic).empty()) decision.reply.topic.clear();
    const auto refuse = [&](WriteError error, std::string text) {
        decision.outcome = WriteRejection{error, std::move(text)};
        return decision;
    };
    if (!message.response_topic.empty()) {
        decision.response_topic_problem = response_topic_problem(message.response_topic);
        if (!decision.response_topic_problem.empty()) {
            return refuse(WriteError::bad_response_topic, "bad response topic");
        }
        decision.reply.topic = message.response_topic;
    }
    if (!target->unknown_tag.empty()) {
        return refuse(WriteError::unknown_tag,
                      "unknown tag " + target->unknown_tag + " in exchange " + plan.spec.name);
    }
    // A retained command would fire again on every reconnect: never act on one. It stays on
    // the broker, refused again at each reconnect, until cleared: say how.
    if (message.retained) {
        return refuse(WriteError::retained,
                      "retained writes are refused; publish without retain, and clear the "
                      "retained one with `mosquitto_pub -r -n -t '" +
                          std::string(topic) + "'`");
    }
    if (plan.spec.direction != core::plan::Direction::produce) {
        return refuse(WriteError::read_only,
                      "exchange " + plan.spec.name + " is consumed: its tags are read-only");
    }
    ExchangeWrite routed{&plan, {}};
    auto rejection =
        collect_writes(plan, target->tag_index, message.payload, options_.profile, routed.writes);
    if (!rejection) rejection = core::write::overlap_rejection(plan, routed.writes);
    if (rejection) return refuse(rejection->error, std::move(rejection->message));
    decision.outcome = std::move(routed);
    return decision;
}

}  // namespace eip2mqtt::app::northbound::json_tree
