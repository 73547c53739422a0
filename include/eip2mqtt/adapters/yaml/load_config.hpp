#pragma once
/// Reads a configuration file (YAML, plus the point-list CSV files it names) into the core's
/// config model, then runs the core's semantic checks. Every problem is reported at once, each
/// with file:line:column; yaml-cpp's exceptions stop here.

#include <cstddef>
#include <stop_token>
#include <string>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::adapters::yaml {

/// The largest configuration file or point list read: 64 MiB, over ten times what a plant of
/// 100,000 inline tags writes (docs/decisions/0001-configurations-of-100000-tags.md). Only regular
/// files are read (a directory, a FIFO or /dev/zero named by mistake is a diagnostic, not a crash,
/// a hang or unbounded memory).
inline constexpr std::size_t max_file_bytes = std::size_t{64} << 20;

/// Loads and validates `path`. Fails with every diagnostic (syntax, unknown keys, bad values,
/// semantic checks) when anything is wrong.
core::Result<core::config::Config, core::config::Diagnostics> load_config(const std::string& path);

/// Same, giving up soon after `stop` is requested, with a diagnostic saying so (a reload's
/// parse when the gateway stops: ReloadWorker).
core::Result<core::config::Config, core::config::Diagnostics> load_config(const std::string& path,
                                                                          std::stop_token stop);

/// Same, from text already in memory; `file` names it in diagnostics and resolves relative
/// `points:` paths (used by tests and the fuzzer).
core::Result<core::config::Config, core::config::Diagnostics> load_config_text(
    const std::string& text, const std::string& file);

}  // namespace eip2mqtt::adapters::yaml
