// Fuzzes the parsers of MQTT write payloads, which come from anyone allowed to publish on a
// `set` topic: hostile JSON must give `malformed` or `wrong_type`, never an exception.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "eip2mqtt/app/northbound/json_tree/write_payload.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view payload(reinterpret_cast<const char*>(data), size);
    (void)eip2mqtt::app::northbound::json_tree::parse_tag_write(payload);
    const auto batch = eip2mqtt::app::northbound::json_tree::parse_exchange_write(payload);
    if (batch && batch.value().empty()) __builtin_trap();  // an empty object fails the write
    return 0;
}
