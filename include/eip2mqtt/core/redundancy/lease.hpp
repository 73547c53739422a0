#pragma once
/// The lease of a hot-standby pair: which of two gateways leads, decided through one retained
/// topic on the broker that both read (the leader's record: its id and an epoch). Pure: every
/// event and every question takes the time, so each rule is tested by passing times.
///
/// The rules, with T = takeover and R = T / 4 (the renewal interval):
/// - The leader publishes its record every R. A renewal counts once the broker acknowledged it,
///   as of the moment it was sent.
/// - The fence: a leader whose newest acknowledged renewal was sent T - 3R / 2 ago or more is
///   fenced at once, whether or not anything ran since (a process resumed after SIGSTOP is
///   fenced at its first question), and steps down. It was sent before the standby received
///   it, so the leader is fenced at least R / 2 before the standby claims.
/// - A standby claims T - R after it last heard another unit's record (or after it started),
///   publishing its record with the highest epoch it knows plus one, so that its claim stands
///   (below) and it takes over T after it last heard the leader.
/// - A claim stands once the broker acknowledged it and R passed without a claim of the same
///   epoch from a unit of higher rank (priority, then id): that one wins, the other stands by.
/// - The new leader produces once it leads and T - 3R / 2 plus a period of its exchanges (the
///   longest) passed since it last heard the old one: that one was fenced by then, so its last
///   datagram is a period behind at least. With periods up to 3R / 2, it produces as it leads.
/// - A standby leaves writes to the leader it heard for T - 3R / 2, while that one may hold its
///   lease, and refuses them after. A unit that started and has read no record yet leaves them
///   too: a leader may live whose record is on its way.
/// - Any unit seeing a record of a newer epoch follows it. Of the same epoch, a claim gives way
///   to a renewal (a leader confirmed: the claim came too late, as one sent by a unit cut off
///   from the broker and delivered once the path is back), a leader ignores a claim (its sender
///   gives way to the renewals, which the broker hands it first), and between two claims, or two
///   renewals, the higher rank wins.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::redundancy {

enum class Role : std::uint8_t { standby, leader };

inline constexpr auto role_names = enum_names<Role>("standby", "leader");

constexpr std::string_view to_string(Role role) { return role_names.name_of(role); }

/// What the leader topic holds.
struct LeaderRecord {
    std::string id;
    std::uint64_t epoch = 0;
    int priority = 0;
    /// A claim not yet confirmed; false: a confirmed leader's renewal.
    bool claim = false;
    /// With `sparkplug:`, a leader's renewal carries the bdSeq of its Sparkplug session, so that
    /// the unit taking over opens one with another (bd_seq.hpp). The lease itself ignores it.
    std::optional<std::uint8_t> bd_seq;

    friend bool operator==(const LeaderRecord&, const LeaderRecord&) = default;
};

struct LeaseSettings {
    std::string id;  ///< gateway.id
    int priority = 0;
    std::chrono::milliseconds takeover{2000};
    /// The longest period of the produced exchanges: a new leader waits this long after the
    /// latest fence of the leader it last heard before it produces.
    std::chrono::milliseconds longest_period{0};
};

/// What to do with a write that reaches this unit.
enum class WritePolicy : std::uint8_t {
    apply,  ///< the leader: stage it
    /// A standby that hears a live leader, which answers it, or a unit whose lease lapsed,
    /// whose successor answers it: left to it (app/redundancy/PairWrites).
    leave_to_leader,
    refuse,  ///< no live leader: answer "standby"
};

class Lease {
public:
    Lease(LeaseSettings settings, MonoTime start);

    /// A record read on the leader topic; nullopt for an empty (cleared) one.
    void on_record(const std::optional<LeaderRecord>& record, MonoTime now);
    /// The broker acknowledged the publication made at `sent_at` (a claim or a renewal).
    void on_acknowledged(MonoTime sent_at);
    /// Advances time: steps down when fenced, claims when the leader is gone, confirms a claim.
    /// Returns the record to publish now (a claim or a renewal), if one is due.
    std::optional<LeaderRecord> tick(MonoTime now);

    Role role(MonoTime now) const;
    bool fenced(MonoTime now) const;
    /// While it leads: the instant its lease lapses (fenced() from then on), as things stand.
    std::optional<MonoTime> leading_until() const;
    /// Whether produced exchanges may send: the leader, unfenced, a period after the latest fence
    /// of the leader it last heard.
    bool may_produce(MonoTime now) const;
    WritePolicy writes(MonoTime now) const;

    std::uint64_t epoch() const { return epoch_; }
    /// When this unit last heard another's record (or started, or stepped down).
    MonoTime last_heard() const { return last_heard_; }
    LeaderRecord own_record() const {
        return {settings_.id, epoch_, settings_.priority, state_ == State::claiming};
    }
    /// The id of the unit this one last heard lead, or its own when leading.
    const std::string& leader_id() const { return leader_id_; }
    std::chrono::milliseconds renew_interval() const { return settings_.takeover / 4; }

private:
    enum class State : std::uint8_t { standby, claiming, leader };

    /// Whether `record` ranks above this unit's own claim of the same epoch.
    bool outranks(const LeaderRecord& record) const;
    /// Whether this unit follows `record`, another unit's of its own epoch.
    bool gives_way(const LeaderRecord& record) const;
    void stand_by(MonoTime now);
    /// How long after its newest acknowledged renewal was sent a leader is fenced.
    std::chrono::milliseconds fence_after() const {
        return settings_.takeover - 3 * renew_interval() / 2;
    }

    LeaseSettings settings_;
    State state_ = State::standby;
    std::uint64_t epoch_ = 0;  ///< the highest seen, or the own claim's
    std::string leader_id_;
    MonoTime last_heard_;    ///< another unit's record, or the start, or a step-down
    MonoTime claimed_at_{};  ///< the own claim's publication
    MonoTime last_sent_{};   ///< the own latest claim or renewal
    std::optional<MonoTime> last_acknowledged_;  ///< sent time of the newest acknowledged one
    /// It stepped down as its lease lapsed and has heard no leader since.
    bool lapsed_ = false;
    /// It read a record on the leader topic (anyone's) since it started.
    bool read_a_record_ = false;
};

}  // namespace eip2mqtt::core::redundancy
