#pragma once
/// Process-wide logging: spdlog to stderr, one line per event. Under journald (JOURNAL_STREAM
/// set) the line carries no timestamp, since the journal adds its own.

#include <string>

namespace eip2mqtt::app {

/// Sets up the default logger; `level` is a spdlog level name (info, debug...). Unknown names
/// fall back to info with a warning.
void setup_logging(const std::string& level);

/// Changes the level of the default logger.
void set_log_level(const std::string& level);

}  // namespace eip2mqtt::app
