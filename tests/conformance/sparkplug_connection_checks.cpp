// The checks of the node's connections: its CONNECT's will and bdSeq, its subscriptions, when
// it may publish, how it disconnects, and one broker at a time.

#include "tests/conformance/sparkplug_connection_checks.hpp"

#include "tests/conformance/sparkplug_checks.hpp"

namespace eip2mqtt::test::conformance::checks {
namespace {

/// The bdSeq of a will or an NBIRTH (an Int64 metric named bdSeq), or nullopt.
std::optional<std::int64_t> bd_seq_of(const SparkplugPayload& payload) {
    const auto* m = metric_named(payload, "bdSeq");
    if (!m || m->datatype() != 4 || !m->has_long_value()) return std::nullopt;
    return int_of(*m);
}

std::optional<SparkplugPayload> will_payload(const NodeConnection& c) {
    if (!c.connect.will) return std::nullopt;
    SparkplugPayload payload;
    if (!payload.ParseFromString(c.connect.will->payload)) return std::nullopt;
    return payload;
}

}  // namespace

Verdict will_registered(const NodeView& view) {
    if (view.connections.empty()) return "the node made no connection";
    for (const auto& c : view.connections) {
        if (!c.connect.will) return "connection " + std::to_string(c.connection) + ": no will";
    }
    return std::nullopt;
}
void break_will_registered(NodeView& view) { view.connections.at(0).connect.will.reset(); }

Verdict will_is_ndeath(const NodeView& view) {
    for (const auto& c : view.connections) {
        if (!c.connect.will) continue;
        const auto& w = *c.connect.will;
        const auto id = "connection " + std::to_string(c.connection) + ": the will ";
        if (w.topic != view.topic("NDEATH")) return id + "is on " + w.topic;
        const auto payload = will_payload(c);
        if (!payload) return id + "is not a Sparkplug B payload";
        if (payload->metrics_size() != 1 || !bd_seq_of(*payload)) {
            return id + "is not one Int64 metric bdSeq";
        }
        if (payload->has_seq()) return id + "has a seq";
    }
    return std::nullopt;
}
void break_will_topic(NodeView& view) { view.connections.at(0).connect.will->topic += "x"; }
void break_will_payload(NodeView& view) { view.connections.at(0).connect.will->payload = "x"; }

Verdict will_qos1_not_retained(const NodeView& view) {
    for (const auto& c : view.connections) {
        if (!c.connect.will) continue;
        if (c.connect.will->qos != 1 || c.connect.will->retain) {
            return "connection " + std::to_string(c.connection) + ": will QoS " +
                   std::to_string(c.connect.will->qos) +
                   (c.connect.will->retain ? ", retained" : "");
        }
    }
    return std::nullopt;
}
void break_will_qos(NodeView& view) { view.connections.at(0).connect.will->qos = 0; }
void break_will_retain(NodeView& view) { view.connections.at(0).connect.will->retain = true; }

Verdict bd_seq_counts_connects(const NodeView& view) {
    // The suite starts on an empty state directory: the first CONNECT ever made says 0.
    std::optional<std::int64_t> last;
    for (const auto& c : view.connections) {
        const auto payload = will_payload(c);
        if (!payload) continue;
        const auto bd_seq = bd_seq_of(*payload);
        if (!bd_seq) continue;
        const auto expected = last ? (*last + 1) % 256 : 0;
        if (*bd_seq != expected) {
            return "connection " + std::to_string(c.connection) + ": will bdSeq " +
                   std::to_string(*bd_seq) + ", not " + std::to_string(expected);
        }
        last = bd_seq;
    }
    return last ? Verdict{} : Verdict{"no will carried a bdSeq"};
}
void break_bd_seq_counts(NodeView& view) {
    auto& will = *view.connections.at(1).connect.will;
    SparkplugPayload payload;
    payload.ParseFromString(will.payload);
    payload.mutable_metrics(0)->set_long_value(payload.metrics(0).long_value() + 2);
    will.payload = payload.SerializeAsString();
}

Verdict nbirth_bd_seq_is_the_wills(const NodeView& view) {
    return each_sent(view, "NBIRTH", [](const NodeConnection& c, std::size_t i) -> Verdict {
        const auto will = will_payload(c);
        const auto& birth = c.packets[i].payload;
        if (!birth || !bd_seq_of(*birth)) return where(c, i) + ": no Int64 bdSeq metric";
        if (!will || bd_seq_of(*will) != bd_seq_of(*birth)) {
            return where(c, i) + ": bdSeq " + std::to_string(*bd_seq_of(*birth)) +
                   ", not the will's";
        }
        return std::nullopt;
    });
}
void break_nbirth_bd_seq(NodeView& view) {
    auto& payload = *first_sent(view, "NBIRTH").payload;
    for (auto& m : *payload.mutable_metrics()) {
        if (m.name() == "bdSeq") m.set_long_value(m.long_value() + 1);
    }
}

}  // namespace eip2mqtt::test::conformance::checks
