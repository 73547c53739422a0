#pragma once
/// Where a write's result goes.

#include <string>

namespace eip2mqtt::app {

class Northbound;

/// The northbound a write came from, and its protocol's address for the answer: for the JSON
/// tree, the MQTT 5 response topic with its correlation data, or the `…/set/result` topic.
struct WriteReply {
    std::string topic;
    std::string correlation_data;
    Northbound* origin = nullptr;  ///< nullptr: nobody to answer
};

}  // namespace eip2mqtt::app
