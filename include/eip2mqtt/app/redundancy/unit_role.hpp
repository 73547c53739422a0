#pragma once
/// This unit's role, as the parts it gates ask it (docs/redundancy.md): one interface, which
/// the pair implements (redundancy::Pair) and, for a single unit, AlwaysLeads, so that no caller
/// asks whether there is a pair. Parts take it one at a time: the FanOut and the
/// ProducerScheduler ask it so far.
///
/// Threading: the loop only.

#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::redundancy {

class UnitRole {
public:
    /// Whether what the exchanges report (samples, statuses, exchange states) goes north now.
    virtual bool leads() const = 0;
    /// Whether produced exchanges may send at `now` (ProducerScheduler).
    virtual bool may_produce(core::MonoTime now) const = 0;

protected:
    UnitRole() = default;
    ~UnitRole() = default;
    UnitRole(const UnitRole&) = default;
    UnitRole& operator=(const UnitRole&) = default;
};

/// The role of a single unit: it always leads.
class AlwaysLeads final : public UnitRole {
public:
    bool leads() const override { return true; }
    bool may_produce(core::MonoTime) const override { return true; }
};

/// The process's one AlwaysLeads.
const UnitRole& always_leads();

}  // namespace eip2mqtt::app::redundancy
