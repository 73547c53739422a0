#include "adapters/mqtt/detail/paho_tokens.hpp"

#include <fmt/format.h>

namespace eip2mqtt::adapters::mqtt::detail {

std::string describe_failure(const ::mqtt::token& tok) {
    const int rc = tok.get_return_code();
    const int reason = tok.get_reason_code();
    std::string text = ::mqtt::exception::error_str(rc);
    if (reason == 0 && rc >= 0x80) {
        // Paho C++ 1.2 reports a refused MQTT 5 CONNACK as a return code holding the reason
        // code (e.g. 135, Not authorized), which error_str does not know.
        return ::mqtt::exception::reason_code_str(rc);
    }
    if (reason != 0) {
        text += fmt::format(" ({})", ::mqtt::exception::reason_code_str(reason));
    }
    return text;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
