#pragma once
/// Process-wide logging: spdlog to stderr, one line per event. Under journald (JOURNAL_STREAM
/// set) the line carries no timestamp, since the journal adds its own. The last warnings are
/// kept in memory too, for the status page.

#include <cstddef>
#include <string>
#include <vector>

namespace eip2mqtt::app {

/// How many of the last warnings and errors recent_warnings() keeps.
inline constexpr std::size_t kept_warnings = 50;

/// Sets up the default logger; `level` is a spdlog level name (info, debug...). Unknown names
/// fall back to info with a warning.
void setup_logging(const std::string& level);

/// The last kept_warnings warnings and errors the default logger wrote since setup_logging(),
/// oldest first, each `2026-11-30T16:12:00.123Z warning: text`. Thread-safe.
std::vector<std::string> recent_warnings();

/// Changes the level of the default logger.
void set_log_level(const std::string& level);

}  // namespace eip2mqtt::app
