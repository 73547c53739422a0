// Fuzzes the parsers of MQTT write payloads, which come from anyone allowed to publish on a
// `set` topic, in every payload profile's forms: hostile JSON must give `malformed` or
// `wrong_type`, never an exception, and an accepted multi-tag write names at least one tag.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "eip2mqtt/app/northbound/json_tree/write_payload.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using eip2mqtt::core::config::PayloadFormat;
    const std::string_view payload(reinterpret_cast<const char*>(data), size);
    for (const auto profile :
         {PayloadFormat::json, PayloadFormat::value, PayloadFormat::umh, PayloadFormat::kepware}) {
        (void)eip2mqtt::app::northbound::json_tree::parse_tag_write(payload, profile);
        const auto batch =
            eip2mqtt::app::northbound::json_tree::parse_exchange_write(payload, profile);
        if (batch && batch.value().empty()) __builtin_trap();  // an empty write fails
    }
    return 0;
}
