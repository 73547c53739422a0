// ChaosRig's recordings turned into the checkers' inputs, and the checkers run over them.

#include <algorithm>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "tests/support/chaos_rig.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;
using core::plan::TagType;
using json = nlohmann::json;

std::int64_t dint_at(std::span<const std::byte> data, std::uint16_t byte) {
    return std::get<std::int64_t>(core::plan::decode_value(data, TagType::dint, {byte, 0}));
}

std::string values_text(std::int64_t count, std::int64_t noise) {
    return "COUNT=" + std::to_string(count) + ",NOISE=" + std::to_string(noise);
}

/// COUNT and NOISE of one of the PLC's datagrams; nullopt when it does not decode.
std::optional<std::pair<std::int64_t, std::int64_t>> counter_of(
    const std::vector<std::byte>& bytes) {
    const auto decoded = core::wire::decode_datagram(bytes);
    if (!decoded.ok() || decoded.value().data.size() < 8) return std::nullopt;
    const auto data = decoded.value().data;
    return std::pair{dint_at(data, 0), dint_at(data, 4)};
}

}  // namespace

std::vector<promises::Produced> ChaosRig::produced() const {
    std::vector<promises::Produced> out;
    for (const auto& d : capture_->datagrams()) {
        const auto decoded = core::wire::decode_datagram(d.bytes);
        if (!decoded.ok() || decoded.value().data.size() < 4) continue;
        const auto value = core::plan::decode_value(decoded.value().data, TagType::real, {0, 0});
        out.push_back({d.source, decoded.value().header.request_id, d.at,
                       static_cast<double>(std::get<float>(value))});
    }
    return out;
}

std::vector<promises::Sent> ChaosRig::sent() const {
    std::vector<promises::Sent> out;
    for (const auto& e : plc_->log()) {
        if (const auto counter = counter_of(e.bytes)) {
            out.push_back({counter->first, values_text(counter->first, counter->second), e.at});
        }
    }
    return out;
}

std::vector<std::int64_t> ChaosRig::required() const {
    // Consumed in order by a unit: its first datagram of the sample is intact and no later
    // sample reached the unit before it (the gateway drops a late or repeated request id).
    std::array<std::set<std::int64_t>, 2> consumed;
    std::array<std::int64_t, 2> newest{0, 0};
    std::map<std::int64_t, std::chrono::milliseconds> sent_at;
    for (const auto& e : plc_->log()) {
        const auto counter = counter_of(e.bytes);
        if (!counter) continue;
        const auto n = counter->first;
        auto& last = newest[e.destination];
        if (n > last && e.intact) consumed[e.destination].insert(n);
        last = std::max(last, n);
        sent_at.emplace(n, e.at);
    }
    // Away from every fault by a takeover (a killed unit's span ends once it is back): what
    // fell closer may be lost legitimately, a unit not yet listening say.
    const auto quiet = [&](std::chrono::milliseconds at) {
        return std::none_of(faulted_.begin(), faulted_.end(), [&](const promises::Span& f) {
            return at >= f.from - settings_.takeover && at <= f.to + settings_.takeover;
        });
    };
    std::vector<std::int64_t> out;
    for (const auto n : consumed[0]) {
        if (consumed[1].count(n) > 0 && quiet(sent_at.at(n))) out.push_back(n);
    }
    return out;
}

std::vector<promises::Published> ChaosRig::published(const std::vector<Received>& messages) const {
    std::vector<promises::Published> out;
    for (const auto& m : messages) {
        if (m.topic != "test/line/_values" && m.topic != "test/line/_history") continue;
        const auto j = json::parse(m.payload, nullptr, false);
        const auto at = std::chrono::duration_cast<std::chrono::milliseconds>(m.at - epoch_);
        if (!j.is_object() || !j.contains("values") || !j["values"].contains("COUNT")) {
            out.push_back({m.topic, -1, m.payload, at});
            continue;
        }
        const auto& v = j["values"];
        const auto count = v["COUNT"].get<std::int64_t>();
        out.push_back({m.topic, count,
                       v.contains("NOISE") ? values_text(count, v["NOISE"].get<std::int64_t>())
                                           : "COUNT=" + std::to_string(count),
                       at});
    }
    return out;
}

namespace {

/// The pair's renewals and the units' roles among `messages`, times since `epoch`.
promises::LeaseHeard lease_of(const std::vector<Received>& messages,
                              std::chrono::steady_clock::time_point epoch) {
    promises::LeaseHeard out;
    auto& [renewals, roles] = out;
    const std::string prefix = "test/_gateway/";
    for (const auto& m : messages) {
        const auto at = std::chrono::duration_cast<std::chrono::milliseconds>(m.at - epoch);
        if (m.topic == "test/_gateway/_pair/turbine/leader") {
            const auto j = json::parse(m.payload, nullptr, false);
            if (j.is_object() && !j.value("claim", false) && j.contains("id")) {
                renewals.push_back({j.value("id", ""), j.value("epoch", 0), at});
            }
        } else if (m.topic.size() > prefix.size() + 5 && m.topic.rfind(prefix, 0) == 0 &&
                   m.topic.substr(m.topic.size() - 5) == "/role") {
            const auto unit = m.topic.substr(prefix.size(), m.topic.size() - prefix.size() - 5);
            roles.push_back({unit, m.payload == "leader", at});
        }
    }
    return out;
}

/// Whether `unit` led at `at`: the last role it said before then was `leader`.
bool led_at(const std::vector<promises::Role>& roles, const std::string& unit,
            promises::Millis at) {
    bool led = false;
    for (const auto& role : roles) {
        if (role.unit == unit && role.at <= at) led = role.leader;
    }
    return led;
}

}  // namespace

std::map<std::string, std::string> ChaosRig::check() const {
    const auto capture = produced();
    const auto sent_samples = sent();
    const auto samples = published(recorder_->messages());
    std::vector<promises::Answer> answers;
    for (const auto& m : recorder_->messages()) {
        if (m.topic != "answers/chaos") continue;
        const auto j = json::parse(m.payload, nullptr, false);
        const bool ok = j.is_object() && j.value("ok", false);
        answers.push_back({m.correlation_data, ok,
                           ok ? "" : (j.is_object() ? j.value("error", m.payload) : m.payload),
                           std::chrono::duration_cast<std::chrono::milliseconds>(m.at - epoch_)});
    }
    const auto period = settings_.produce_period;
    const auto lapse = 5 * settings_.takeover / 8 + settings_.consume_period;
    using namespace promises;
    std::map<std::string, std::string> out;
    const auto add = [&](const std::string& name, const std::vector<std::string>& found) {
        out[name] = report(name, found);
    };
    add("one producer", one_producer(capture, period, period / 5));
    const auto lease = lease_of(recorder_->messages(), epoch_);
    const auto& [renewals, roles] = lease;
    add("leadership present", leadership_present(capture, lease, settings_.takeover, period,
                                                 settings_.takeover / 4, unreachable_, end_));
    add("leader kept",
        leader_kept(renewals, roles, unit_faults_, settings_.takeover / 2, 5 * settings_.takeover));
    add("published was sent", published_was_sent(sent_samples, samples));
    add("samples once, in order",
        samples_once_in_order(sent_samples, required(), samples, disrupted_, lapse));
    // What may have been lost with a write: a killed broker's unsaved messages. Answered twice
    // alike: across a cut path (QoS 1's repeat), and across a killed leader (the unit taking
    // over answers again a write its image lists and whose answer it did not hear: the answer
    // may never have left, docs/redundancy.md).
    auto repeats = disrupted_;
    for (const auto& kill : units_killed_) {
        if (led_at(roles, kill.unit, kill.span.from)) repeats.push_back(kill.span);
    }
    // A live leader answers within a production, a save and a broker round trip; a cut one
    // takes over's worth more (the pair's write horizon, app/redundancy/pair_writes.hpp).
    add("writes answered once",
        writes_answered_once(writes_, answers, capture, settings_.takeover, broker_lost_,
                             2 * settings_.takeover + 2 * settings_.produce_period, repeats));
    return out;
}

std::string ChaosRig::story() const {
    std::ostringstream out;
    out << "seed " << settings_.seed << ", " << writes_.size() << " writes, " << required().size()
        << " samples required\n";
    for (const auto& line : story_) out << "  " << line << "\n";
    for (const auto& m : recorder_->messages()) {
        if (m.topic.find("/role") == std::string::npos &&
            m.topic != "test/_gateway/_pair/turbine/leader") {
            continue;
        }
        out << "  " << std::chrono::duration_cast<std::chrono::milliseconds>(m.at - epoch_).count()
            << " ms: " << m.topic << " " << m.payload << "\n";
    }
    for (int unit = 0; unit < 2; ++unit) {
        out << "--- unit " << unit << " ---\n" << earlier_logs_[unit];
        if (gateways_[unit]) out << gateways_[unit]->output();
    }
    // Where each answer went, as the broker saw it: received from a unit, sent on to the
    // recorder, or dropped for a client that fell behind.
    out << "--- broker: answers and drops ---\n";
    std::istringstream log(broker_.log());
    for (std::string line; std::getline(log, line);) {
        if (line.find("answers/chaos") != std::string::npos ||
            line.find("dropped") != std::string::npos) {
            out << line << "\n";
        }
    }
    return out.str();
}

}  // namespace eip2mqtt::test
