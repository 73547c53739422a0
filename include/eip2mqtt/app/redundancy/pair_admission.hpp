#pragma once
/// What a unit of a pair does with the writes that reach it (docs/redundancy.md), the pair's
/// WriteRole: the leader applies them; a unit that does not lead leaves each to the leader, a
/// live one or the unit that leads next (PairWrites), unanswered and counted, but refuses
/// `standby` when no leader answers, and always on the command port (its own address, which no
/// leader answers). At a takeover, a write that the old leader never answered is applied when
/// the image already holds what it writes, else refused `standby`.
///
/// Threading: the loop only.

#include <functional>

#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/app/redundancy/unit_role.hpp"
#include "eip2mqtt/core/redundancy/lease.hpp"

namespace eip2mqtt::app::redundancy {

class PairAdmission final : public WriteRole {
public:
    struct Hooks {
        /// Whether this unit takes a write now (the lease's Lease::writes).
        std::function<core::redundancy::WritePolicy()> policy;
        /// Takes each write left to the leader (PairWrites).
        std::function<void(WriteRequest&& request)> leave;
        /// Whether the produced image already holds what `write` writes (Exchanges::holds).
        std::function<bool(const ExchangeWrite& write)> holds;
    };

    explicit PairAdmission(Hooks hooks) : hooks_(std::move(hooks)) {}

    WriteTurn admit_write(WriteRequest& request, core::write::WriteCounters& counters) override;
    WriteTurn settle_write(const WriteRequest& request,
                           core::write::WriteCounters& counters) override;
    core::write::WriteRejection refusal() const override;

private:
    Hooks hooks_;
};

}  // namespace eip2mqtt::app::redundancy
