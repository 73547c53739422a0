#pragma once
/// What `eip2mqtt check` says of the `redundancy:` section (docs/redundancy.md): the pair's
/// name, its takeover and how often the lease is renewed.

#include <string>

#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app::redundancy {

/// One line, ending in a line break; empty without a pair.
std::string section_summary(const core::config::RedundancySection& section);

}  // namespace eip2mqtt::app::redundancy
