#pragma once
/// Outside text (a client's topic, a name from a file, what a node told) as it may stand in one
/// log line, a terminal or a YAML comment.

#include <string>
#include <string_view>

namespace eip2mqtt::core {

/// `text` cut to `max_bytes` (with "..." when cut) and with its control bytes written as \xNN,
/// so that no client can break a log line or forge the next one.
std::string printable(std::string_view text, std::size_t max_bytes = 200);

/// As printable, and every byte from 0x80 up written as \xNN too: for text a node told
/// (identifications, NAK strings), in no known encoding, shown on a terminal or written into
/// YAML, where no byte of it may end a line, start an escape sequence or a YAML line break.
/// Its own output comes back unchanged.
std::string printable_ascii(std::string_view text, std::size_t max_bytes = 200);

}  // namespace eip2mqtt::core
