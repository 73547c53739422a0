#pragma once
/// The fixed parts of the generated plugin, in this order, lua_dissector writing the configured
/// exchanges after the prelude. The prelude expects a table `settings` (data_port, command_port,
/// clock_tolerance_ms) and defines `exchange(ex, define_tags)`; the dissection part uses what the
/// exchanges defined.

#include <string_view>

namespace eip2mqtt::app::dissector::detail {

/// Protocol, header fields, expert entries, tag types, and `exchange`.
extern const std::string_view lua_prelude;
/// Per-exchange statistics (`tshark -z eip2mqtt,stat`), fed by the dissection part.
extern const std::string_view lua_statistics;
/// The consumer rules (docs/protocol.md §4) as expert info, the dissector, its registration.
extern const std::string_view lua_dissection;
/// The command protocol on `settings.command_port` (docs/protocol.md §9).
extern const std::string_view lua_commands;

}  // namespace eip2mqtt::app::dissector::detail
