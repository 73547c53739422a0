#pragma once
/// Outside text (a client's topic, a name from a file) as it may stand in one log line.

#include <string>
#include <string_view>

namespace eip2mqtt::core {

/// `text` cut to `max_bytes` (with "..." when cut) and with its control bytes written as \xNN,
/// so that no client can break a log line or forge the next one.
std::string printable(std::string_view text, std::size_t max_bytes = 200);

}  // namespace eip2mqtt::core
