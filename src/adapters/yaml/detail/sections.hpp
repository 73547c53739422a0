#pragma once
/// The readers of the configuration's sections, one concern each: each reads its section's
/// node into the model and reports what does not read through `reader`.
///
/// Module-private to src/adapters/yaml.

#include "adapters/yaml/detail/point_lists.hpp"
#include "adapters/yaml/detail/reader.hpp"

namespace eip2mqtt::adapters::yaml::detail {

// read_sections.cpp
void read_gateway(Reader& reader, const Node& node, const Mark& at, Config& config);
void read_mqtt(Reader& reader, const Node& node, const Mark& at, Config& config);
void read_metrics(Reader& reader, const Node& node, const Mark& at, Config& config);
void read_sparkplug(Reader& reader, const Node& node, const Mark& at, Config& config);

// read_eip.cpp: with its commands and multicast groups.
void read_eip(Reader& reader, const Node& node, const Mark& at, Config& config);

// read_redundancy.cpp
void read_redundancy(Reader& reader, const Node& node, const Mark& at, Config& config);

/// read_exchanges.cpp: the exchanges, their tags and the rows of the point lists they name.
void read_exchanges(Reader& reader, PointLists& point_lists, const Node& node, const Mark& at,
                    Config& config);

}  // namespace eip2mqtt::adapters::yaml::detail
