#include "adapters/mqtt/detail/paho_trace.hpp"

#include <MQTTAsync.h>

namespace eip2mqtt::adapters::mqtt::detail {

bool quiet_paho_trace(const char* requested_trace) {
    if (requested_trace != nullptr && *requested_trace != '\0') {
        return false;  // the user asked for Paho's trace: its level stays
    }
    ::MQTTAsync_setTraceLevel(MQTTASYNC_TRACE_ERROR);
    return true;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
