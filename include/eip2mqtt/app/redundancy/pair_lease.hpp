#pragma once
/// The lease of a hot-standby pair at run time (docs/redundancy.md): the core's Lease
/// (core/redundancy/lease.hpp, where its rules are) fed from the pair's own MQTT connection. It
/// reads the retained leader topic, publishes this unit's claims and renewals there (retained,
/// QoS 1: a renewal counts once the broker acknowledged it), and says on the unit's role topic,
/// retained, whether it leads. It subscribes the connection to the images' topics as well, which
/// PairImages reads. Its renewals carry the leader's watermarks, and it hands those of the
/// leader's renewals it reads on (PairHistory). The gateway asks it, with the time, whether to
/// produce, publish the tag tree and take writes.
///
/// Threading: the loop only.

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publisher.hpp"
#include "eip2mqtt/app/redundancy/leader_record.hpp"
#include "eip2mqtt/core/redundancy/lease.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::app::redundancy {

struct PairTopics {
    std::string leader;  ///< {base}/_gateway/_pair/{pair}/leader
    std::string role;    ///< {base}/_gateway/{id}/role
    std::string images;  ///< {base}/_gateway/_pair/{pair}/image, a level per exchange below
};

PairTopics pair_topics(const std::string& base_topic, const std::string& pair,
                       const std::string& id);

/// The pair connection's will: the leader topic cleared (retained, empty). Either unit's will
/// clears it; the leader writes it again at its next renewal. Nothing is decided on it: a
/// standby takes over a takeover after it last heard the leader, cleared or not.
adapters::mqtt::Message pair_will(const PairTopics& topics);

class PairLease {
public:
    using RoleChanged = std::function<void(core::redundancy::Role role)>;
    /// The bdSeq of this unit's open Sparkplug session; nullopt while none is open.
    using BdSeqSource = std::function<std::optional<std::uint8_t>()>;

    /// `publisher` (the pair's connection) must outlive the lease; `on_role` runs on each
    /// change of role, after the role topic was published.
    PairLease(core::redundancy::LeaseSettings settings, PairTopics topics,
              adapters::mqtt::Publisher& publisher, core::MonoTime start, RoleChanged on_role);

    /// With `sparkplug:`: each renewal carries what `source` says (LeaderRecord::bd_seq).
    void set_bd_seq_source(BdSeqSource source) { bd_seq_source_ = std::move(source); }
    /// The bdSeq of the newest record read on the leader topic that carried one, of the
    /// lease's epoch or a newer one (a deposed leader's renewal delivered late is not): the
    /// last Sparkplug session of the pair this unit knows of.
    std::optional<std::uint8_t> heard_bd_seq() const { return heard_bd_seq_; }
    using WatermarksNow = std::function<Watermarks()>;
    using WatermarksHeard = std::function<void(Watermarks&& watermarks)>;
    /// `now` gives the watermarks each renewal carries; `heard` gets those of each renewal read
    /// from the unit this one follows (core/redundancy/acked_watermarks.hpp).
    void set_watermarks(WatermarksNow now, WatermarksHeard heard) {
        watermarks_now_ = std::move(now);
        watermarks_heard_ = std::move(heard);
    }

    /// Runs when this unit leads on under a higher epoch (a stale claim's, renewed over):
    /// what it publishes under its epoch (the images) goes again.
    void set_on_epoch_raised(std::function<void()> handler) {
        on_epoch_raised_ = std::move(handler);
    }

    /// After each (re)connect of the pair's connection: the role topic again.
    void on_connected();
    /// Whether the pair's connection is up, asked before each tick (Lease::on_connection).
    void on_connection(bool up, core::MonoTime now) { lease_.on_connection(up, now); }
    void on_message(const adapters::mqtt::Incoming& message, core::MonoTime now);
    /// The acknowledgement token of a claim or renewal (its sending time).
    void on_acknowledged(std::uint64_t token);
    /// Publishes a due claim or renewal; a fence or a claim confirmed changes the role.
    void tick(core::MonoTime now);

    bool leading(core::MonoTime now) const {
        return lease_.role(now) == core::redundancy::Role::leader;
    }
    bool may_produce(core::MonoTime now) const { return lease_.may_produce(now); }
    core::redundancy::WritePolicy writes(core::MonoTime now) const { return lease_.writes(now); }
    const core::redundancy::Lease& lease() const { return lease_; }
    /// The highest epoch of a record read from the other unit, claim or renewal: 0 until one.
    std::uint64_t others_epoch() const { return others_epoch_; }
    /// The highest epoch of a renewal read from the other unit (it led under it): 0 until one.
    std::uint64_t others_renewed_epoch() const { return others_renewed_; }

private:
    void publish_role(core::redundancy::Role role);
    void follow_role(core::MonoTime now);

    core::redundancy::Lease lease_;
    std::chrono::milliseconds takeover_;
    PairTopics topics_;
    adapters::mqtt::Publisher& publisher_;
    RoleChanged on_role_;
    BdSeqSource bd_seq_source_;
    std::optional<std::uint8_t> heard_bd_seq_;
    WatermarksNow watermarks_now_;
    WatermarksHeard watermarks_heard_;
    Watermarks heard_;  ///< what the last record read carried
    core::redundancy::Role role_ = core::redundancy::Role::standby;
    std::uint64_t led_epoch_ = 0;              ///< the epoch it leads under
    std::optional<core::MonoTime> led_until_;  ///< its lease as of the last tick it led
    std::uint64_t claimed_epoch_ = 0;          ///< of its latest claim (logged once)
    std::uint64_t others_epoch_ = 0;
    std::uint64_t others_renewed_ = 0;
    std::function<void()> on_epoch_raised_;
    adapters::mqtt::Message message_;
};

}  // namespace eip2mqtt::app::redundancy
