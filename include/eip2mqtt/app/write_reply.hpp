#pragma once
/// Where a write's result goes.

#include <string>

namespace eip2mqtt::app {

/// The MQTT 5 response topic with its correlation data, or the `…/set/result` topic.
struct WriteReply {
    std::string topic;
    std::string correlation_data;
};

}  // namespace eip2mqtt::app
