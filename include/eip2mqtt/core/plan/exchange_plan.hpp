#pragma once
/// What the gateway knows of one exchange, built once from a validated configuration.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/plan/location.hpp"
#include "eip2mqtt/core/plan/tag_plan.hpp"
#include "eip2mqtt/core/plan/topic_template.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::plan {

enum class Direction : std::uint8_t { consume, produce };

inline constexpr auto direction_names = enum_names<Direction>("consume", "produce");

constexpr std::string_view to_string(Direction direction) {
    return direction_names.name_of(direction);
}

/// Which time a consumed exchange's tags carry (core::exchange::RemoteProducerClock): `automatic`
/// (YAML `auto`) the producer's while its clock is within the tolerance of the receive time,
/// `producer` the producer's whenever the datagram has one, `receive` always the receive time.
enum class TimestampSource : std::uint8_t { automatic, producer, receive };

inline constexpr auto timestamp_source_names =
    enum_names<TimestampSource>("auto", "producer", "receive");

constexpr std::string_view to_string(TimestampSource source) {
    return timestamp_source_names.name_of(source);
}
constexpr std::optional<TimestampSource> parse_timestamp_source(std::string_view text) {
    return timestamp_source_names.parse(text);
}

/// What an exchange takes from the gateway section unless it says otherwise.
struct ExchangeDefaults {
    TimestampSource timestamp = TimestampSource::automatic;
    std::chrono::milliseconds clock_tolerance{2000};
};

/// An exchange as configured, independent of topics.
struct ExchangeSpec {
    std::string name;
    Direction direction = Direction::consume;
    wire::ProducerId producer_id;
    std::uint32_t exchange_id = 0;
    std::optional<std::uint16_t> length;  ///< data bytes; default: end of the last tag
    wire::Signature signature;            ///< 0.0 = not used
    std::chrono::milliseconds period{1000};
    std::optional<std::chrono::milliseconds> timeout;  ///< consume; default 3 x period; 0 disables
    std::optional<TimestampSource> timestamp;          ///< consume; default: the gateway's
    std::optional<std::chrono::milliseconds> clock_tolerance;  ///< consume; default: the gateway's
    std::optional<std::uint32_t>
        source;                ///< consume: IPv4 (host order) the datagrams must come from
    std::string destination;   ///< produce: host or host:port
    std::string topic;         ///< under base_topic
    std::string points;        ///< point-list CSV file, relative to the config file
    bool publish_raw = false;  ///< what a tag that does not say takes (TagExtras::publish_raw)
    Location location;         ///< nearer than the gateway's, farther than a tag's
    std::vector<TagSpec> tags;

    friend bool operator==(const ExchangeSpec&, const ExchangeSpec&) = default;
};

/// An exchange with its topics and derived figures.
struct ExchangePlan {
    ExchangeSpec spec;
    std::uint16_t length = 0;              ///< resolved data length, 1..1400
    std::chrono::milliseconds timeout{0};  ///< resolved update timeout; 0 disables
    TimestampSource timestamp = TimestampSource::automatic;  ///< resolved
    std::chrono::milliseconds clock_tolerance{2000};         ///< resolved
    std::string topic;                                       ///< {base}/{exchange.topic}
    std::string status_topic;                                ///< topic + "/_status"
    std::string values_topic;                                ///< topic + "/_values" (batch mode)
    std::string meta_topic;     ///< topic + "/_meta": the exchange and its tags described, retained
    std::string set_topic;      ///< topic + "/set" (atomic multi-tag writes)
    std::vector<TagPlan> tags;  ///< in configuration order
    /// Each tag's topic, in the order of `tags`, where one is not {topic}/{tag name} (a
    /// template, a tag's `topic` or `topic_name`); empty when every tag's is: the default
    /// layout keeps no topic per tag.
    std::vector<std::string> tag_topics;

    wire::ExchangeKey key() const { return {spec.producer_id, spec.exchange_id}; }
    /// The topic of `tag`, one of `tags`: its entry of tag_topics, else {topic}/{tag name}.
    std::string tag_topic(const TagPlan& tag) const;
    /// The same into `out` (replacing its content, reusing its buffer).
    void tag_topic_into(const TagPlan& tag, std::string& out) const;
    /// Equal plans mean nothing to do on reload: the running exchange is kept as it is.
    friend bool operator==(const ExchangePlan&, const ExchangePlan&) = default;
};

/// Length a spec resolves to: its `length`, else the end of its last tag.
std::uint16_t resolved_length(const ExchangeSpec& spec);

/// How tags' topics are laid out: mqtt.topic_template and the gateway's location (null: the
/// default template, no location).
struct TopicLayout {
    const TopicTemplate* topic_template = nullptr;
    const Location* gateway_location = nullptr;
};

/// The topic of `tag` of the exchange `spec`: its `topic` when it has one, else the template
/// filled in (a location key from the tag, else the exchange, else the gateway).
std::string expand_tag_topic(const TopicLayout& layout, const std::string& base_topic,
                             const ExchangeSpec& spec, const TagSpec& tag);

/// Builds the plan of a spec that passed validation.
/// Takes the spec by value: a caller done with it moves it in, and its tags are copied once
/// (into `tags`), not twice.
ExchangePlan make_exchange_plan(ExchangeSpec spec, const std::string& base_topic,
                                const ExchangeDefaults& defaults = {},
                                const TopicLayout& layout = {});

}  // namespace eip2mqtt::core::plan
