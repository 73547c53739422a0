#pragma once
/// Where a message on a `…/set` topic goes and what it asks (docs/mqtt-api.md "Writes"):
/// the exchange and tag its topic names, where its result goes, and either the validated writes to
/// stage or the reason it is refused. Pure: no sockets, no clock, no logging, so hostile input
/// can be driven through it in a unit test or a fuzzer. The gateway stages what it returns.
///
/// Threading: the loop only.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <variant>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::app::northbound::json_tree {

struct WriteRouterOptions {
    std::string base_topic;
    /// mqtt.allow_response_topics_under_base: see WriteRouter::route.
    bool allow_response_topics_under_base = false;
    /// mqtt.payload: its profile's write forms are taken beside the json ones.
    core::config::PayloadFormat profile = core::config::PayloadFormat::json;
};

/// What a message on one of our `…/set` topics asks: the validated writes (ExchangeWrite, whose
/// `producer` is the plan given to add()) or why it is refused.
struct WriteDecision {
    WriteReply reply;  ///< where the result goes; an empty topic: nowhere a broker accepts
    std::variant<ExchangeWrite, core::write::WriteRejection> outcome;
    /// Why the response topic was refused (for the log), when it was.
    std::string response_topic_problem;
};

class WriteRouter {
public:
    explicit WriteRouter(WriteRouterOptions options = {});

    /// Forgets every exchange (before a reload adds them again).
    void clear();
    /// Routes writes to `plan`'s `set` topics; those of a consumed exchange are refused as
    /// read-only. `plan` must outlive the router's use of it (until clear()): it is the handle
    /// of a produced exchange's writes.
    void add(const core::plan::ExchangePlan& plan);
    void set_options(WriteRouterOptions options) { options_ = std::move(options); }

    /// The topic filters to subscribe to: one per depth of `…/set` topic (`{base}/+/+/set`...)
    /// rather than one per tag, so a few SUBSCRIBEs hear every tag's `set` topic whatever the
    /// configuration's size. Tags laid out by a template may be anywhere, and an MQTT 5 broker
    /// delivers a message once per filter it matches: then each exchange's `set` and each
    /// produced tag's are subscribed exactly, and none overlaps another.
    std::vector<std::string> subscriptions() const;

    /// Decides what `message` asks; nullopt when its topic is not a `set` topic of ours, or
    /// when its payload is empty (a retained write being cleared): it is ignored. The response
    /// topic must be one every broker accepts (no wildcard, valid UTF-8, at most 65,535 bytes) and,
    /// unless allowed by the options, not a topic under the base topic other than below a `set`
    /// level: otherwise the write is refused with `bad_response_topic`, answered on `{set
    /// topic}/result`.
    std::optional<WriteDecision> route(const adapters::mqtt::Incoming& message) const;

private:
    struct Route {
        const core::plan::ExchangePlan* plan = nullptr;
    };
    /// The exchange a `set` topic's stem names and, for `{exchange topic}/{tag}`, the tag.
    struct Target {
        const Route* route = nullptr;
        std::optional<std::size_t> tag_index;  ///< nullopt: a multi-tag write (or unknown tag)
        std::string unknown_tag;               ///< a tag level naming no tag of the exchange
    };
    std::optional<Target> find_target(std::string_view stem) const;
    std::vector<std::string> exact_subscriptions() const;
    std::string response_topic_problem(const std::string& topic) const;

    WriteRouterOptions options_;
    /// Exchanges by their full topic; a tag's `{exchange topic}/{tag}/set` is resolved through
    /// the exchange and the tag's name, so there is no entry per tag.
    std::unordered_map<std::string, Route> exchanges_;
    /// Tags whose topic is their own (ExchangePlan::tag_topics), by that topic.
    struct TagRoute {
        const Route* route = nullptr;
        std::size_t tag_index = 0;
    };
    std::unordered_map<std::string, TagRoute> tags_;
};

}  // namespace eip2mqtt::app::northbound::json_tree
