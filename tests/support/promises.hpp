#pragma once
/// Checkers of a hot-standby pair's promises (docs/redundancy.md), as pure functions over what a
/// test recorded: the datagrams captured on the segment, the samples the PLC sent, the MQTT
/// messages, the writes and their answers, and the faults the test caused. No clock, no socket:
/// every time is an offset from the start of the run, taken by the test as it recorded; each
/// checker returns one line per violation (empty: the promise held), so that a failed run names
/// what broke, where and when. docs/testing.md says how each one reads real timing.

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace eip2mqtt::test::promises {

using Millis = std::chrono::milliseconds;

/// A datagram of the produced exchange, captured on the segment: which unit sent it (its
/// source address), its request id, when it arrived (the kernel's receive time).
struct Produced {
    std::string producer;
    std::uint16_t request_id = 0;
    Millis at{0};
    double value = 0;  ///< the written tag's value it carries
};

/// Never two producers: a datagram of one unit between two of another's (they produce at once),
/// or less than `period - slack` after another unit's (the old leader's last datagram is a
/// period behind the new leader's first, at least). `slack` is the capture's own error (the
/// senders' scheduling on a loaded machine), never more than a small part of the period.
std::vector<std::string> one_producer(const std::vector<Produced>& capture, Millis period,
                                      Millis slack);

/// A span of the run, [from, to).
struct Span {
    Millis from{0};
    Millis to{0};
};

/// A renewal on the pair's leader topic (a record without `claim`), and a unit's role message.
struct Renewal {
    std::string unit;
    int epoch = 0;
    Millis at{0};
};
struct Role {
    std::string unit;
    bool leader = false;
    Millis at{0};
};
/// What a subscriber heard of the lease, in the order heard.
struct LeaseHeard {
    std::vector<Renewal> renewals;
    std::vector<Role> roles;
};

/// Leadership never absent: the produced stream (all units together) never pauses longer than
/// `takeover + period + slack`, unless the pause overlaps a span of `excused` (no unit could
/// reach the broker, and the time both take to be back). Measured from the first datagram to
/// `end` (a pause at the end counts too). Where the leader stood down within the pause, it
/// counts from the last renewal of its lease heard before that, if later than the last
/// datagram: a standby counts its takeover from the last record it heard (docs/redundancy.md),
/// and a leader cut off stops reaching the PLCs at once while a renewal it sent in the cut
/// reaches the broker when its path is back. A leader that renews and never produces is caught.
std::vector<std::string> leadership_present(const std::vector<Produced>& capture,
                                            const LeaseHeard& lease, Millis takeover, Millis period,
                                            Millis slack, const std::vector<Span>& excused,
                                            Millis end);

/// A fault of one unit's broker path (cut, stalled, delayed, the unit stopped or killed), or of
/// every unit's (`unit` empty: the broker stopped).
struct UnitFault {
    std::string unit;
    Span span;
};

/// A live leader is never deposed: a unit that says `standby` after `leader` while it was
/// renewing (its last renewal less than `renewing` before) stood down for a newer epoch, which
/// only a claim made while its claimant could not hear it gives, unless the unit's own path
/// failed. A unit fenced by its own fault stops renewing `5 * takeover / 8` before it stands
/// down; renewals it queued during a stall may arrive with its `standby`: its own faults, until
/// `back` after they end (its reconnection), are not judged. Nor is a unit whose renewals
/// reached the broker `renewing` or more apart in its last lease (`2 * renewing` before it
/// stood down): its path stalled with no fault injected (a loaded machine, a broker busy with
/// the other unit's backlog), and a lease not acknowledged in time is given up by design.
std::vector<std::string> leader_kept(const std::vector<Renewal>& renewals,
                                     const std::vector<Role>& roles,
                                     const std::vector<UnitFault>& faults, Millis renewing,
                                     Millis back);

/// A sample the PLC sent: its number (the counter tag's value, one per datagram), the values it
/// carried as canonical text (`COUNT=5,NOISE=17`), and when it left.
struct Sent {
    std::int64_t sample = 0;
    std::string values;
    Millis at{0};
};

/// A sample published on `_values` or `_history`, as the recorder received it.
struct Published {
    std::string topic;
    std::int64_t sample = 0;
    std::string values;  ///< canonical text, as in Sent
    Millis at{0};
};

/// Nothing published that was not sent: every published sample's values are those of a
/// datagram the PLC's log holds (forged datagrams from other sources never appear).
std::vector<std::string> published_was_sent(const std::vector<Sent>& sent,
                                            const std::vector<Published>& published);

/// The samples of `_values` and `_history`: each of `required` (samples delivered intact to
/// both units, away from any fault) on one topic or the other at least once; never twice on one
/// topic; never older than one before it on its topic. Excused, as docs/redundancy.md and
/// docs/mqtt-api.md allow: what a unit had handed to its connection when a span of `disrupted`
/// began (a broker path cut, stalled or stopped) may come again (QoS 1's repeat) or late, once
/// the path is back. A unit that leads keeps handing samples to its connection until its lease
/// lapses, `lapse` after the span began at the latest (5/8 of the takeover, plus a period): a
/// repeat or a step back is excused when its sample was sent before `from + lapse` of such a
/// span and arrived after the span ended.
std::vector<std::string> samples_once_in_order(const std::vector<Sent>& sent,
                                               const std::vector<std::int64_t>& required,
                                               const std::vector<Published>& published,
                                               const std::vector<Span>& disrupted, Millis lapse);

/// A write the test published, with its own value (unique in the run).
struct Write {
    std::string id;  ///< its correlation data
    double value = 0;
    Millis at{0};
};

/// An answer received for write `id`: `ok`, or the error it gave.
struct Answer {
    std::string id;
    bool ok = false;
    std::string error;
    Millis at{0};
};

/// Every write answered once (never twice, never two answers that disagree, never
/// unanswered by the end), and each `ok` carried on the wire: a datagram captured after the
/// write was sent, and no later than `reach` after its answer arrived (the capture's clock and
/// the recorder's are read apart), holds its value, or that of a write sent after it (writes
/// that arrive together are applied to one production, the last value of a tag winning).
/// Excused: a write never answered that was sent less than `answer_within` before a span of
/// `broker_lost` began, or during it (Mosquitto killed, with what it had not saved: the write,
/// its answer or the image its answer waited for may have been lost with it). A loaded
/// machine is slower than the horizon: the longest the run took to answer a write away from every
/// span (its own pace) is added to `answer_within`. Excused too, as
/// docs/mqtt-api.md allows: the same answer again, arrived after a span of `disrupted` began,
/// for a write sent during it or less than `answer_within` before it began (the answer was in
/// flight, its acknowledgement lost with the path: QoS 1's repeat; or the unit taking over
/// answered again what the old leader's image listed, the old leader's answer killed with it
/// or held in its cut connection until the path came back).
std::vector<std::string> writes_answered_once(const std::vector<Write>& writes,
                                              const std::vector<Answer>& answers,
                                              const std::vector<Produced>& capture, Millis reach,
                                              const std::vector<Span>& broker_lost = {},
                                              Millis answer_within = Millis{0},
                                              const std::vector<Span>& disrupted = {});

/// Every violation of every checker on one line each, prefixed with the checker's name.
std::string report(const std::string& checker, const std::vector<std::string>& violations);

}  // namespace eip2mqtt::test::promises
