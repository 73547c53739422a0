#pragma once
/// What the gateway knows of one tag, built once from the configuration.

#include <chrono>
#include <optional>
#include <string>

#include "eip2mqtt/core/out_of_line.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/location.hpp"
#include "eip2mqtt/core/plan/scaling.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"

namespace eip2mqtt::core::plan {

/// The settings few tags use, kept out of line by TagSpec.
struct TagExtras {
    std::string unit;
    std::string description;  ///< carried north where a protocol has room (Sparkplug)
    std::optional<double> min;
    std::optional<double> max;
    std::optional<Value> initial;  ///< produced exchanges: value when no image is persisted
    double max_writes_per_s = 0;   ///< writes accepted per second (burst of 1 s); 0: no limit
    /// `scale`: the published value is this engineering value of the wire's, and writes are
    /// in its units (`min`, `max` and `initial` too; `initial` is kept here in its raw form).
    std::optional<Scaling> scale;
    /// `deadband: {percent: P}`: P % of the engineering span. TagSpec::deadband holds the
    /// absolute band it makes, which is what reports compare against.
    std::optional<double> deadband_percent;
    bool publish_raw = false;  ///< JSON payloads add the wire's value as "raw"
    /// Strings: trailing NULs and spaces are removed from what is published (`trim: false`
    /// keeps them).
    bool trim = true;
    /// What `{tag}` stands for in mqtt.topic_template; empty: the name.
    std::string topic_name;
    /// The tag's whole topic, the template left aside; empty: the template's.
    std::string topic;
    /// The tag's own location keys, nearer than its exchange's and the gateway's.
    Location location;

    friend bool operator==(const TagExtras&, const TagExtras&) = default;
};

/// A tag as configured (YAML `tags:` entry or point-list row). A gateway holds one per tag
/// (100,000 in a large plant), so it is kept to 64 bytes: what every tag uses inline, the rest in
/// TagExtras behind one pointer that stays null for a tag that sets none of it.
struct TagSpec {
    std::string name;
    Address address;
    TagType type = TagType::byte;
    bool writable = false;
    /// `count`: elements of `type` at consecutive offsets (bits at consecutive bits); a
    /// string's `length` in bytes. 1 is a scalar, which every other tag is.
    std::uint16_t count = 1;
    double deadband = 0.0;             ///< absolute; 0 publishes any change
    std::chrono::seconds refresh{60};  ///< republish at least this often

    const std::string& unit() const { return extras_.get().unit; }
    const std::string& description() const { return extras_.get().description; }
    const std::optional<double>& min() const { return extras_.get().min; }
    const std::optional<double>& max() const { return extras_.get().max; }
    const std::optional<Value>& initial() const { return extras_.get().initial; }
    double max_writes_per_s() const { return extras_.get().max_writes_per_s; }
    const std::optional<Scaling>& scale() const { return extras_.get().scale; }
    const std::optional<double>& deadband_percent() const { return extras_.get().deadband_percent; }
    bool publish_raw() const { return extras_.get().publish_raw; }
    bool trim() const { return extras_.get().trim; }
    const std::string& topic_name() const { return extras_.get().topic_name; }
    const std::string& topic() const { return extras_.get().topic; }
    const Location& location() const { return extras_.get().location; }
    /// True for a tag whose value is a List: a `count` of a type other than string.
    bool is_array() const { return count > 1 && type != TagType::string; }

    /// The rarely set settings to write (loaders and tests), allocated on first use.
    TagExtras& mutable_extras() { return extras_.mutable_get(); }

    /// Compares contents: a tag whose extras were written with their defaults equals one that
    /// never had any (reload keeps exchanges whose plans compare equal).
    friend bool operator==(const TagSpec&, const TagSpec&) = default;

private:
    OutOfLine<TagExtras> extras_;
};

/// A tag of an ExchangePlan. Its topics are not kept: a gateway holds one TagPlan per tag
/// (100,000 in a large plant, where a topic is rarely short enough to need no heap block).
/// ExchangePlan::tag_topic builds the topic when publishing, which costs what copying a stored
/// one into the message did; writes are resolved by exchange topic and tag name.
struct TagPlan {
    TagSpec spec;

    friend bool operator==(const TagPlan&, const TagPlan&) = default;
};

}  // namespace eip2mqtt::core::plan
