#include "tests/support/gateway_binary.hpp"

#include <cstdlib>

namespace eip2mqtt::test {

const std::string& gateway_binary() {
    static const std::string path = [] {
        const char* chosen = std::getenv("EIP2MQTT_TEST_BINARY");
        return std::string(chosen != nullptr && *chosen != '\0' ? chosen : EIP2MQTT_BUILT_BINARY);
    }();
    return path;
}

}  // namespace eip2mqtt::test
