#pragma once
/// What the gateway knows of one tag, built once from the configuration.

#include <chrono>
#include <optional>
#include <string>

#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value.hpp"

namespace eip2mqtt::core::plan {

/// A tag as configured (YAML `tags:` entry or point-list row). A gateway holds one per tag
/// (100,000 in a large plant): `writable` sits next to `type` to fill padding (152 bytes, not 160).
struct TagSpec {
    std::string name;
    Address address;
    TagType type = TagType::byte;
    bool writable = false;
    std::string unit;
    double deadband = 0.0;             ///< absolute; 0 publishes any change
    std::chrono::seconds refresh{60};  ///< republish at least this often
    std::optional<double> min;
    std::optional<double> max;
    std::optional<Value> initial;  ///< produced exchanges: value when no image is persisted
    double max_writes_per_s = 0;   ///< writes accepted per second (burst of 1 s); 0: no limit

    friend bool operator==(const TagSpec&, const TagSpec&) = default;
};

/// A tag with its precomputed topic. Its write topic, topic + "/set", is not kept: a gateway
/// holds one TagPlan per tag (100,000 in a large plant) and resolves writes by exchange topic
/// and tag name instead.
struct TagPlan {
    TagSpec spec;
    std::string topic;  ///< {base}/{exchange.topic}/{name}

    friend bool operator==(const TagPlan&, const TagPlan&) = default;
};

}  // namespace eip2mqtt::core::plan
