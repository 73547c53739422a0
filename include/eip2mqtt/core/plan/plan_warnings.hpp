#pragma once
/// What `check` warns about in a valid exchange: settings that work, yet leave a plant
/// situation the gateway cannot recover from by itself.

#include <string>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"

namespace eip2mqtt::core::plan {

/// One sentence per warning, without the exchange's name; empty when there is nothing to say.
std::vector<std::string> plan_warnings(const ExchangePlan& plan);

}  // namespace eip2mqtt::core::plan
