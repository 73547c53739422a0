#pragma once
/// What `check` warns about in a valid exchange: settings that work, yet leave a plant
/// situation the gateway cannot recover from by itself, or that a consumer downstream reads
/// otherwise than meant.

#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::plan {

/// What the warnings need to know beyond the exchange.
struct WarningContext {
    /// `mqtt.version` is 3 (3.1.1): the version of the brokers that map `.` in a topic to `/`
    /// (RabbitMQ's MQTT plugin), so a dot changes the topic a subscriber must use.
    bool mqtt_3_1_1 = false;
};

/// One sentence per warning, without the exchange's name; empty when there is nothing to say.
std::vector<std::string> plan_warnings(const ExchangePlan& plan,
                                       const WarningContext& context = {});

}  // namespace eip2mqtt::core::plan
