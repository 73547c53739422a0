#pragma once
/// This unit's role, as the parts it gates ask it (docs/redundancy.md): one interface, which
/// the pair implements (redundancy::Pair) and, for a single unit, AlwaysLeads, so that no caller
/// asks whether there is a pair. The parts ask it: the FanOut (what goes north), the
/// ProducerScheduler (may I produce now), the DatagramRouter (whose request ids to follow),
/// each ExchangeProducer (which images changed, when a write is answered) and the
/// WriteDispatcher (what happens to this write: WriteRole).
///
/// Threading: the loop only.

#include <cstdint>
#include <functional>
#include <string>

#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/write/write_counters.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::app {
class ExchangeProducer;
struct WriteReply;
struct WriteRequest;
}  // namespace eip2mqtt::app

namespace eip2mqtt::app::redundancy {

/// What becomes of a write that reached this unit (WriteRole).
enum class WriteTurn : std::uint8_t {
    apply,    ///< staged on its exchange, as any write
    taken,    ///< moved from the request: the role keeps it (another unit may answer it)
    refused,  ///< answered WriteRole::refusal()
};

/// The part of the role that the writes ask (WriteDispatcher). Each call may count what it
/// did in `counters`, the dispatcher's.
class WriteRole {
public:
    /// A write that reached this unit now.
    virtual WriteTurn admit_write(WriteRequest& request, core::write::WriteCounters& counters) = 0;
    /// A write that this unit takes over, which the unit before it took and never answered
    /// (WriteDispatcher::settle): applied as any write would be, or refused (never `taken`).
    virtual WriteTurn settle_write(const WriteRequest& request,
                                   core::write::WriteCounters& counters) = 0;
    /// What a refused write is answered.
    virtual core::write::WriteRejection refusal() const = 0;

protected:
    WriteRole() = default;
    ~WriteRole() = default;
    WriteRole(const WriteRole&) = default;
    WriteRole& operator=(const WriteRole&) = default;
};

class UnitRole : public WriteRole {
public:
    /// Whether what the exchanges report (samples, statuses, exchange states) goes north now.
    virtual bool leads() const = 0;
    /// Whether produced exchanges may send at `now` (ProducerScheduler).
    virtual bool may_produce(core::MonoTime now) const = 0;

    /// Whether datagrams of the exchanges this unit produces may come from another unit, which
    /// sends them in its stead (DatagramRouter): heard, they are counted, not unknown.
    virtual bool hears_produced() const = 0;
    /// Whether such a datagram, heard at `now`, sets its producer's next request id: this unit
    /// goes on from the other's last, so consumers see one producer, not a restart.
    virtual bool follows_produced(core::MonoTime now) const = 0;

    /// `producer`'s image, changed by writes, left in a datagram (ExchangeProducer).
    virtual void image_changed(const ExchangeProducer& producer) = 0;
    /// How `producer` answers a write it accepted (`write_id`: its number there): `answer`
    /// runs now, or once the role lets it.
    virtual void answer_write(const ExchangeProducer& producer, std::uint64_t write_id,
                              const WriteReply& reply, std::function<void()> answer) = 0;
    /// The role as the status page shows it, JSON: `null` for a unit alone.
    virtual std::string status_json() const { return "null"; }

protected:
    UnitRole() = default;
    ~UnitRole() = default;
    UnitRole(const UnitRole&) = default;
    UnitRole& operator=(const UnitRole&) = default;
};

/// The role of a single unit: it always leads, no other unit sends its exchanges, and it
/// applies every write and answers it at once.
class AlwaysLeads final : public UnitRole {
public:
    bool leads() const override { return true; }
    bool may_produce(core::MonoTime) const override { return true; }
    bool hears_produced() const override { return false; }
    bool follows_produced(core::MonoTime) const override { return false; }
    void image_changed(const ExchangeProducer&) override {}
    void answer_write(const ExchangeProducer&, std::uint64_t, const WriteReply&,
                      std::function<void()> answer) override {
        answer();
    }
    WriteTurn admit_write(WriteRequest&, core::write::WriteCounters&) override {
        return WriteTurn::apply;
    }
    WriteTurn settle_write(const WriteRequest&, core::write::WriteCounters&) override {
        return WriteTurn::apply;
    }
    core::write::WriteRejection refusal() const override { return {}; }  ///< never asked
};

/// The process's one AlwaysLeads (it holds no state).
UnitRole& always_leads();

}  // namespace eip2mqtt::app::redundancy
