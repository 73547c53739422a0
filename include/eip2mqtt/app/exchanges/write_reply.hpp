#pragma once
/// Where a write's result goes.

#include <cstdint>
#include <string>

#include "eip2mqtt/core/write/write_origin.hpp"

namespace eip2mqtt::app {

class Northbound;

using core::write::WriteOrigin;

/// The northbound a write came from, and its protocol's address for the answer: for the JSON
/// tree, the MQTT 5 response topic with its correlation data, or the `…/set/result` topic.
struct WriteReply {
    std::string topic;
    std::string correlation_data;
    Northbound* origin = nullptr;  ///< nullptr: nobody to answer
    WriteOrigin via = WriteOrigin::mqtt;
    std::uint64_t log_id = 0;  ///< its entry in the write log (WriteLog); 0: none
};

}  // namespace eip2mqtt::app
