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
/// - A claim stands once the broker acknowledged it, the unit heard it back (its subscription
///   hears its own records), and R passed without a claim of the same epoch from a unit of
///   higher rank (priority, then id): that one wins, the other stands by. Heard back, the
///   claim came after everything the broker had queued for the unit before taking it: an
///   acknowledgement can overtake those (the broker sends it at once, and holds messages
///   beyond the unit's in-flight window), so a unit cut off from the broker, whose claims
///   and the leader's renewals crossed, leads on no acknowledgement before it read the
///   renewals. A claimant that hears the leader its claim named renew after what it named,
///   before its claim came back, gives way: its claim was made without hearing that renewal.
///   After, the renewal is one the broker took after the claim (a leader stalled on its way
///   to the broker, fenced meanwhile): the claim stands.
/// - The new leader produces once it leads and T - 3R / 2 plus a period of its exchanges (the
///   longest) passed since it last heard the old one: that one was fenced by then, so its last
///   datagram is a period behind at least. With periods up to 3R / 2, it produces as it leads.
/// - A unit that does not lead leaves every write to the leader: a live one answers it, else
///   the unit that leads next settles it (app/redundancy/PairWrites), having heard no answer.
///   It refuses none, not even with no leader heard: it may be cut off without knowing, or
///   lose its claim, and a refusal could contradict the unit that answers.
/// - Any unit seeing a record of a newer epoch follows it. Of the same epoch, a claim gives way
///   to a renewal (a leader confirmed: the claim came too late, as one sent by a unit cut off
///   from the broker and delivered once the path is back), a leader ignores a claim (its sender
///   gives way to the renewals, which the broker hands it first), and between two claims, or two
///   renewals, the higher rank wins.
/// - Every record carries its beat (the instant it was sent, by its sender's clock), and a
///   claim names the record its claimant last heard (LeaderMark): a leader whose lease holds
///   ignores a claim naming anything but its own newest acknowledged renewal, whatever its
///   epoch. It was made by a unit that could not hear that renewal (cut off, its claim
///   delivered once the path came back): the leader takes the claim's epoch if higher and
///   renews at once, and a claimant hearing a renewal of its epoch gives way, as does a unit
///   that led on such a claim when the leader its claim named renews after what it named. A
///   standby hearing the leader it follows renew after what it heard follows it still, even
///   below an epoch its own failed claim raised.
/// - A unit claims only while its pair connection is up, and not again while a claim of its
///   own was never acknowledged: a claim sits in no buffer behind another. Once that one is
///   acknowledged (the path is back) or the connection is made anew, it waits T - R again.

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

/// What a claim names: the record its claimant last heard (of another unit).
struct LeaderMark {
    std::string id;
    std::uint64_t epoch = 0;
    std::uint64_t beat = 0;

    friend bool operator==(const LeaderMark&, const LeaderMark&) = default;
};

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
    /// When it was sent, in nanoseconds of its sender's steady clock (0: a record that has
    /// none, from an earlier version). Only its sender compares it, to its own.
    std::uint64_t beat = 0;
    /// A claim's: the record its claimant last heard; nullopt when it heard none.
    std::optional<LeaderMark> heard;

    /// The same lead: who, which epoch, a claim or not, and its bdSeq. The beat and what a claim
    /// heard say when, not who (compare them by name).
    friend bool operator==(const LeaderRecord& a, const LeaderRecord& b) {
        return a.id == b.id && a.epoch == b.epoch && a.priority == b.priority &&
               a.claim == b.claim && a.bd_seq == b.bd_seq;
    }
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
    /// A unit that does not lead: left to the leader, a live one or the unit that leads next,
    /// which settles it (app/redundancy/PairWrites).
    leave_to_leader,
    refuse,  ///< answer "standby" (an admission's own; Lease::writes never says it)
};

class Lease {
public:
    Lease(LeaseSettings settings, MonoTime start);

    /// Whether the pair connection is up, as of `now` (asked before each tick): while it is
    /// down, no claim; once it is up again, a standby waits T - R before it claims.
    void on_connection(bool up, MonoTime now);
    /// A record read on the leader topic; nullopt for an empty (cleared) one. Returns whether
    /// this unit follows it (another unit's record that it now takes as the lead).
    bool on_record(const std::optional<LeaderRecord>& record, MonoTime now);
    /// The broker acknowledged the publication made at `sent_at` (a claim or a renewal).
    void on_acknowledged(MonoTime sent_at);
    /// Advances time: steps down when fenced, claims when the leader is gone, confirms a claim.
    /// Returns the record to publish now (a claim or a renewal), if one is due.
    std::optional<LeaderRecord> tick(MonoTime now);

    Role role(MonoTime now) const;
    bool fenced(MonoTime now) const;
    /// Claiming, and the claim was heard back: what the broker took before it has come.
    bool claim_heard_back() const { return state_ == State::claiming && echoed_; }
    /// While it leads: the instant its lease lapses (fenced() from then on), as things stand.
    std::optional<MonoTime> leading_until() const;
    /// Whether produced exchanges may send: the leader, unfenced, a period after the latest fence
    /// of the leader it last heard.
    bool may_produce(MonoTime now) const;
    /// Whether it leads at `now` and the broker acknowledged a renewal sent since it began to:
    /// it reached the broker as leader (a takeover's replay waits for it).
    bool renewed_since_leading(MonoTime now) const {
        return role(now) == Role::leader && last_acknowledged_ && *last_acknowledged_ >= led_at_;
    }
    WritePolicy writes(MonoTime now) const;

    std::uint64_t epoch() const { return epoch_; }
    /// When this unit last heard another's record (or started, or stepped down).
    MonoTime last_heard() const { return last_heard_; }
    /// Its record as of its latest claim or renewal (beat and, on a claim, what it heard).
    LeaderRecord own_record() const;
    /// The id of the unit this one last heard lead, or its own when leading.
    const std::string& leader_id() const { return leader_id_; }
    const std::string& id() const { return settings_.id; }
    std::chrono::milliseconds renew_interval() const { return settings_.takeover / 4; }

private:
    enum class State : std::uint8_t { standby, claiming, leader };

    /// Whether `record` ranks above this unit's own claim of the same epoch.
    bool outranks(const LeaderRecord& record) const;
    /// Whether this unit follows `record`, another unit's of its own epoch.
    bool gives_way(const LeaderRecord& record) const;
    /// Whether `record` is a renewal of the unit `mark` names, sent after the one it names.
    static bool renews_after(const LeaderRecord& record, const std::optional<LeaderMark>& mark);
    /// Whether `claim`, another unit's, names anything but this leader's newest acknowledged
    /// renewal: made by a unit that could not hear it.
    bool stale(const LeaderRecord& claim) const;
    void follow(const LeaderRecord& record, MonoTime now);
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
    MonoTime led_at_{};      ///< its claim confirmed: it leads from then
    MonoTime last_sent_{};   ///< the own latest claim or renewal
    std::optional<MonoTime> last_acknowledged_;  ///< sent time of the newest acknowledged one
    /// The newest record of another unit it followed; what its claims name.
    std::optional<LeaderMark> heard_;
    /// What its current claim (or the claim it leads on) named.
    std::optional<LeaderMark> named_;
    bool connected_ = true;
    bool echoed_ = false;  ///< its current claim was heard back
    /// The sending time of its claim that lapsed unacknowledged: no claim while it is set.
    std::optional<MonoTime> unanswered_claim_;
    /// That claim was acknowledged since the last tick: the path is back.
    bool path_back_ = false;
    /// A stale claim came while it led: it renews at its next tick.
    bool reassert_ = false;
};

}  // namespace eip2mqtt::core::redundancy
