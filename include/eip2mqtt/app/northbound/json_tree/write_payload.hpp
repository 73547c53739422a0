#pragma once
/// Parsing of MQTT write payloads with a real JSON library (nlohmann-json), as docs/mqtt-api.md
/// specifies: a tag write is `42`, `true`, `12.5` or `{"value":42}`; an exchange write is
/// `{"SPEED_SP":3100,"START":true}` (each value a scalar or {"value": scalar}). Hostile input
/// (deep nesting, huge numbers, invalid UTF-8, trailing garbage) yields `malformed`, never an
/// exception.

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/result.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::app::northbound::json_tree {

/// One tag's input. Strings and other non-scalars are `wrong_type`; unparsable text, objects
/// without exactly the key "value", arrays and empty payloads are `malformed`. A payload
/// profile's own forms are taken too: umh `{"value":…,"timestamp_ms":…}`, kepware `{"v":…}`,
/// and with value, text that is not JSON is a string's text.
core::Result<core::write::WriteInput, core::write::WriteRejection> parse_tag_write(
    std::string_view payload,
    core::config::PayloadFormat profile = core::config::PayloadFormat::json);

/// One tag's name with its input.
using NamedWrite = std::pair<std::string, core::write::WriteInput>;

/// A multi-tag write: tag names with their inputs, in payload order. A non-object, an empty
/// object, or any value that is not a scalar or {"value": scalar} fails the whole write.
/// With kepware, Kepware's `[{"id":"exchange.tag","v":…},…]` too, each id as written (the
/// router takes `exchange.` off).
core::Result<std::vector<NamedWrite>, core::write::WriteRejection> parse_exchange_write(
    std::string_view payload,
    core::config::PayloadFormat profile = core::config::PayloadFormat::json);

}  // namespace eip2mqtt::app::northbound::json_tree
