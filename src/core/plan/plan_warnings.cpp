#include "eip2mqtt/core/plan/plan_warnings.hpp"

namespace eip2mqtt::core::plan {

std::vector<std::string> plan_warnings(const ExchangePlan& plan) {
    std::vector<std::string> warnings;
    if (plan.spec.direction == Direction::consume && plan.timeout.count() == 0) {
        // A restart is recognised by the producer's time moving forward while its request ids
        // went back; without timestamps only the update timeout resynchronises.
        warnings.push_back(
            "timeout_ms is 0: if its producer sends no timestamps, after a restart of the "
            "producer every datagram is dropped as out of order until its request ids pass "
            "the last one seen (up to 32,768 datagrams); keep an update timeout (the default "
            "is 3 periods)");
    }
    return warnings;
}

}  // namespace eip2mqtt::core::plan
