#pragma once
/// The Wireshark plugin `eip2mqtt dissector` writes: a Lua 5.2 script (the Lua of Debian 12's
/// Wireshark 4.0) that decodes the data port as protocol `eip2mqtt`, each configured exchange's
/// tags as typed fields, with the gateway's consumer rules as expert info and per-exchange
/// statistics, and the command port as protocol `eip2mqtt_cmd`.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::app::dissector {

/// What the plugin needs beyond the exchanges.
struct DissectorSettings {
    std::uint16_t data_port = 18246;    ///< eip.port
    std::uint16_t command_port = 7937;  ///< eip.commands.port
    /// gateway.clock_tolerance_ms: judges the clocks of exchanges nobody configured.
    std::chrono::milliseconds clock_tolerance{2000};
    std::string source;  ///< the configuration it was made from, named in its first line
};

/// The plugin's text. Each exchange's tags are fields `eip2mqtt.<exchange>.<tag>`, their parts
/// from FieldParts (exchanges unique among exchanges, tags within their exchange), labelled with
/// the configured name and unit. When two exchanges share a (producer id, exchange id) pair,
/// the first one decodes it. Deterministic: the same plans give the same text.
std::string lua_dissector(const std::vector<core::plan::ExchangePlan>& plans,
                          const DissectorSettings& settings);

}  // namespace eip2mqtt::app::dissector
