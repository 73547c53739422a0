#pragma once
/// A tag's engineering keys (docs/configuration.md "Engineering values"): `scale`, `type_eu`,
/// `deadband` written as a mapping, and `initial` in engineering units. What they mean is the
/// core's to check (core/config); here they are read, and a scale takes its kind from the keys
/// it has.
///
/// Module-private to src/adapters/yaml.

#include <optional>

#include "adapters/yaml/detail/key_readers.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/plan/scaling.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// What a tag's engineering keys gave, until its other keys are read too.
struct EngineeringDraft {
    std::optional<core::plan::Scaling> scale;
    std::optional<core::plan::TagType> eu_type;
    Mark eu_type_mark;
    std::optional<double> deadband_percent;
    /// The marks of the keys inside `scale` and `deadband`, as "scale.raw", for the core's
    /// messages.
    std::vector<std::pair<std::string, Mark>> marks;
};

bool read_scale(KeyValue& v, EngineeringDraft& d);
bool read_type_eu(KeyValue& v, EngineeringDraft& d);
/// `deadband: 0.5` (absolute, into `absolute`) or `deadband: {percent: 0.5}`.
bool read_deadband(KeyValue& v, double& absolute, EngineeringDraft& d);

/// Once all of a tag's keys are read: its scale with its `type_eu`, the percent deadband as the
/// absolute band of the tag's span, and the marks. False when the tag is to be left out.
bool finish_engineering(Reader& reader, EngineeringDraft& d, TagConfig& tag);

/// A scaled tag's `initial`: a number in engineering units, kept as the raw value it becomes.
std::optional<core::plan::Value> read_initial_eu(Reader& reader, const Node& value,
                                                 const core::plan::Scaling& scale,
                                                 core::plan::TagType wire, const Mark& at);

}  // namespace eip2mqtt::adapters::yaml::detail
