#pragma once
/// The lines the two YAML skeletons (sniff's, from the wire, and discover's, from the command
/// port) write alike, so that both read the same to whoever pastes them into a configuration.

#include <cstdint>
#include <string>

#include "eip2mqtt/core/exchange/wire_survey.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// The period_ms the validation accepts (config.cpp), which a skeleton's period is held within.
inline constexpr std::uint32_t min_period_ms = 2;
inline constexpr std::uint32_t max_period_ms = 3600000;

/// The first lines of a consumed exchange's item: its name, direction and key.
void item_head(const core::wire::ExchangeKey& key, std::string& out);

/// Where an exchange's datagrams go, for its `# destination:` line: the group of a multicast
/// one with the setting that joins it. `kind` is one that names an address (not unknown).
std::string destination_text(core::exchange::DestinationKind kind, std::uint32_t address);

}  // namespace eip2mqtt::adapters::yaml::detail
