#include "tests/support/promises.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <sstream>
#include <utility>

namespace eip2mqtt::test::promises {
namespace {

std::string ms(Millis t) { return std::to_string(t.count()) + " ms"; }

std::vector<Produced> by_time(std::vector<Produced> capture) {
    std::stable_sort(capture.begin(), capture.end(),
                     [](const Produced& a, const Produced& b) { return a.at < b.at; });
    return capture;
}

/// When a pause after the datagram at `from` starts counting: at the last renewal of the lease
/// in force at `from` (the last renewal heard by then) heard before its holder said `standby`,
/// if it said so before `to`; else at `from`.
Millis takeover_counted_from(const LeaseHeard& lease, Millis from, Millis to) {
    const Renewal* in_force = nullptr;
    for (const auto& r : lease.renewals) {
        if (r.at <= from) in_force = &r;
    }
    if (in_force == nullptr) return from;
    const auto stood_down =
        std::find_if(lease.roles.begin(), lease.roles.end(), [&](const Role& r) {
            return r.unit == in_force->unit && !r.leader && r.at > from && r.at < to;
        });
    if (stood_down == lease.roles.end()) return from;
    Millis last = from;
    for (const auto& r : lease.renewals) {
        if (r.epoch == in_force->epoch && r.at > from && r.at <= stood_down->at) last = r.at;
    }
    return last;
}

bool overlaps(Millis from, Millis to, const std::vector<Span>& spans) {
    return std::any_of(spans.begin(), spans.end(),
                       [&](const Span& s) { return s.from < to && from < s.to; });
}

/// When each sample first left the PLC.
std::map<std::int64_t, Millis> first_sent(const std::vector<Sent>& sent) {
    std::map<std::int64_t, Millis> out;
    for (const auto& s : sent) {
        const auto [it, added] = out.emplace(s.sample, s.at);
        if (!added) it->second = std::min(it->second, s.at);
    }
    return out;
}

}  // namespace

std::vector<std::string> one_producer(const std::vector<Produced>& capture, Millis period,
                                      Millis slack) {
    std::vector<std::string> out;
    const auto sorted = by_time(capture);
    for (std::size_t i = 1; i < sorted.size(); ++i) {
        const auto& before = sorted[i - 1];
        const auto& after = sorted[i];
        if (before.producer == after.producer) continue;
        const auto gap = after.at - before.at;
        if (gap >= period - slack) continue;
        out.push_back(before.producer + " (request id " + std::to_string(before.request_id) +
                      ", at " + ms(before.at) + ") then " + after.producer + " (request id " +
                      std::to_string(after.request_id) + ", at " + ms(after.at) +
                      "): two producers " + ms(gap) + " apart, within a period of " + ms(period));
    }
    return out;
}

std::vector<std::string> leadership_present(const std::vector<Produced>& capture,
                                            const LeaseHeard& lease, Millis takeover, Millis period,
                                            Millis slack, const std::vector<Span>& excused,
                                            Millis end) {
    std::vector<std::string> out;
    const auto sorted = by_time(capture);
    if (sorted.empty()) return {"nothing was produced at all"};
    const auto bound = takeover + period + slack;
    const auto pause = [&](Millis last, Millis to, const std::string& what) {
        const auto from = takeover_counted_from(lease, last, to);
        if (to - from <= bound || overlaps(from, to, excused)) return;
        const auto counted = from > last ? "; the last datagram at " + ms(last) +
                                               ", the lease's last renewal heard at " + ms(from)
                                         : std::string();
        out.push_back("nobody produced from " + ms(from) + " to " + ms(to) + " (" + ms(to - from) +
                      ", more than takeover + period + slack = " + ms(bound) + counted + ") " +
                      what);
    };
    for (std::size_t i = 1; i < sorted.size(); ++i) {
        pause(sorted[i - 1].at, sorted[i].at,
              "after " + sorted[i - 1].producer + "'s request id " +
                  std::to_string(sorted[i - 1].request_id) + ", until " + sorted[i].producer +
                  "'s");
    }
    pause(sorted.back().at, end, "until the end of the run");
    return out;
}

std::vector<std::string> leader_kept(const std::vector<Renewal>& renewals,
                                     const std::vector<Role>& roles,
                                     const std::vector<UnitFault>& faults, Millis renewing,
                                     Millis back) {
    std::vector<std::string> out;
    std::map<std::string, bool> leads;
    for (const auto& role : roles) {
        const bool led = leads[role.unit];
        leads[role.unit] = role.leader;
        if (!led || role.leader) continue;
        const auto own_fault = std::any_of(faults.begin(), faults.end(), [&](const UnitFault& f) {
            return (f.unit.empty() || f.unit == role.unit) && f.span.from <= role.at &&
                   role.at <= f.span.to + back;
        });
        if (own_fault) continue;
        const Renewal* last = nullptr;
        const Renewal* newer = nullptr;  // the other unit's first renewal after the step down
        bool stalled = false;            // two of its renewals `renewing` apart in its last lease
        for (const auto& r : renewals) {
            if (r.unit == role.unit && r.at <= role.at) {
                stalled |= last != nullptr && r.at + 2 * renewing >= role.at &&
                           r.at - last->at >= renewing;
                last = &r;
            }
            if (r.unit != role.unit && r.at >= role.at && newer == nullptr) newer = &r;
        }
        if (last == nullptr || role.at - last->at >= renewing || stalled) continue;
        out.push_back(role.unit + " stood down at " + ms(role.at) + " while renewing (epoch " +
                      std::to_string(last->epoch) + ", last renewal at " + ms(last->at) +
                      ") with no fault of its own" +
                      (newer ? ": " + newer->unit + " renews epoch " +
                                   std::to_string(newer->epoch) + " from " + ms(newer->at)
                             : ""));
    }
    return out;
}

std::vector<std::string> published_was_sent(const std::vector<Sent>& sent,
                                            const std::vector<Published>& published) {
    std::set<std::pair<std::int64_t, std::string>> on_wire;
    for (const auto& s : sent) on_wire.emplace(s.sample, s.values);
    std::vector<std::string> out;
    for (const auto& p : published) {
        if (on_wire.count({p.sample, p.values}) > 0) continue;
        out.push_back(p.topic + " at " + ms(p.at) + " carried " + p.values +
                      ", which the PLC never sent");
    }
    return out;
}

std::vector<std::string> samples_once_in_order(const std::vector<Sent>& sent,
                                               const std::vector<std::int64_t>& required,
                                               const std::vector<Published>& published,
                                               const std::vector<Span>& disrupted, Millis lapse) {
    const auto left = first_sent(sent);
    // In flight when a broker path went down, delivered once it was back: QoS 1's repeat.
    const auto in_flight = [&](const Published& p) {
        const auto it = left.find(p.sample);
        if (it == left.end()) return false;
        return std::any_of(disrupted.begin(), disrupted.end(), [&](const Span& d) {
            return it->second < d.from + lapse && d.to <= p.at;
        });
    };
    std::vector<std::string> out;
    std::map<std::string, std::set<std::int64_t>> seen;
    std::map<std::string, std::int64_t> newest;
    std::set<std::int64_t> anywhere;
    for (const auto& p : published) {
        anywhere.insert(p.sample);
        auto& topic_seen = seen[p.topic];
        const bool twice = !topic_seen.insert(p.sample).second;
        const auto it = newest.find(p.topic);
        const bool back = it != newest.end() && p.sample < it->second;
        if ((twice || back) && !in_flight(p)) {
            out.push_back(p.topic + " at " + ms(p.at) + ": sample " + std::to_string(p.sample) +
                          (twice ? " twice" : "") + (twice && back ? " and" : "") +
                          (back ? " back in time, after " + std::to_string(it->second) : ""));
        }
        if (!back) newest[p.topic] = p.sample;
    }
    for (const auto sample : required) {
        if (anywhere.count(sample) == 0) {
            out.push_back("sample " + std::to_string(sample) +
                          ", delivered to both units, never published");
        }
    }
    return out;
}

namespace {

/// The longest any write took to be answered, among those no span of `spans` touched between
/// the write and its first answer: how slow the machine answered on its own, this run.
Millis slowest_quiet_answer(const std::vector<Write>& writes,
                            const std::map<std::string, std::vector<const Answer*>>& by_write,
                            const std::vector<Span>& lost, const std::vector<Span>& cut) {
    Millis slowest{0};
    for (const auto& w : writes) {
        const auto found = by_write.find(w.id);
        if (found == by_write.end() || found->second.empty()) continue;
        const auto answered = found->second.front()->at;
        const auto touches = [&](const Span& s) { return s.from <= answered && w.at <= s.to; };
        if (std::none_of(lost.begin(), lost.end(), touches) &&
            std::none_of(cut.begin(), cut.end(), touches)) {
            slowest = std::max(slowest, answered - w.at);
        }
    }
    return slowest;
}

}  // namespace

std::vector<std::string> writes_answered_once(const std::vector<Write>& writes,
                                              const std::vector<Answer>& answers,
                                              const std::vector<Produced>& capture, Millis reach,
                                              const std::vector<Span>& broker_lost,
                                              Millis answer_within,
                                              const std::vector<Span>& disrupted) {
    std::map<std::string, std::vector<const Answer*>> by_write;
    for (const auto& a : answers) by_write[a.id].push_back(&a);
    const auto text = [](const Answer& a) {
        return (a.ok ? std::string("ok") : a.error) + " at " + ms(a.at);
    };
    // A loaded machine answers later than the horizon says: its own pace is added to it.
    const auto within =
        answer_within + slowest_quiet_answer(writes, by_write, broker_lost, disrupted);
    std::vector<std::string> out;
    for (const auto& w : writes) {
        const auto& got = by_write[w.id];
        const std::string name =
            "write " + w.id + " (" + std::to_string(w.value) + ", at " + ms(w.at) + ")";
        if (got.empty()) {
            const bool lost = std::any_of(broker_lost.begin(), broker_lost.end(), [&](auto& s) {
                return w.at + within >= s.from && w.at <= s.to;
            });
            if (!lost) out.push_back(name + " never answered");
            continue;
        }
        const bool agree = std::all_of(got.begin(), got.end(), [&](const Answer* a) {
            return a->ok == got[0]->ok && a->error == got[0]->error;
        });
        const auto repeated = [&](std::size_t i) {  // copy i sent again around a disruption
            return std::any_of(disrupted.begin(), disrupted.end(), [&](const Span& d) {
                return w.at + answer_within >= d.from && w.at <= d.to && d.from <= got[i]->at;
            });
        };
        std::size_t excused = 0;
        for (std::size_t i = 1; agree && i < got.size(); ++i) excused += repeated(i) ? 1 : 0;
        if (got.size() > 1 && excused + 1 < got.size()) {
            std::string all;
            for (const auto* a : got) all += (all.empty() ? "" : ", ") + text(*a);
            out.push_back(name +
                          (agree ? " answered " + std::to_string(got.size()) + " times: "
                                 : " contradicted: ") +
                          all);
        }
        for (const auto* a : got) {
            if (!a->ok) continue;
            const auto carries = [&](const Produced& d) {
                if (d.at < w.at || d.at > a->at + reach) return false;
                return std::any_of(writes.begin(), writes.end(), [&](const Write& later) {
                    return later.at >= w.at && later.value == d.value;
                });
            };
            if (std::none_of(capture.begin(), capture.end(), carries)) {
                out.push_back(name + " answered ok, but no datagram carried it");
            }
            break;
        }
    }
    return out;
}

std::string report(const std::string& checker, const std::vector<std::string>& violations) {
    std::ostringstream out;
    for (const auto& v : violations) out << checker << ": " << v << "\n";
    return out.str();
}

}  // namespace eip2mqtt::test::promises
