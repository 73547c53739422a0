#pragma once
/// One tag's value as an exchange reports it: the tag by its index in the exchange plan.

#include <cstddef>

#include "eip2mqtt/core/plan/value.hpp"

namespace eip2mqtt::core::plan {

struct TagSample {
    std::size_t tag = 0;  ///< index in the exchange plan's tags
    Value value;
};

}  // namespace eip2mqtt::core::plan
