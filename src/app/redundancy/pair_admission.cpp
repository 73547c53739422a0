#include "eip2mqtt/app/redundancy/pair_admission.hpp"

#include <variant>

namespace eip2mqtt::app::redundancy {

WriteTurn PairAdmission::admit_write(WriteRequest& request, core::write::WriteCounters& counters) {
    using core::redundancy::WritePolicy;
    const auto policy = hooks_.policy();
    if (policy == WritePolicy::apply) return WriteTurn::apply;
    if (policy == WritePolicy::leave_to_leader && request.reply.via != WriteOrigin::commands) {
        ++counters.writes_left_to_leader;
        hooks_.leave(std::move(request));
        return WriteTurn::taken;
    }
    return WriteTurn::refused;
}

WriteTurn PairAdmission::settle_write(const WriteRequest& request,
                                      core::write::WriteCounters& counters) {
    const auto* write = std::get_if<ExchangeWrite>(&request.outcome);
    if (write && !hooks_.holds(*write)) {
        ++counters.writes_settled_standby;
        return WriteTurn::refused;
    }
    if (write) ++counters.writes_settled_applied;
    return WriteTurn::apply;
}

core::write::WriteRejection PairAdmission::refusal() const {
    return {core::write::WriteError::standby, "standby"};
}

}  // namespace eip2mqtt::app::redundancy
