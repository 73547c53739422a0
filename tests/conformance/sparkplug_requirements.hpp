#pragma once
/// The edge-node requirements of the Sparkplug B 3.0 specification, each named by its tck-id
/// and judged over a NodeView: a check that says what breaks it (nothing when it holds), and an
/// alteration of a conformant view that breaks it, so that every check is seen to fail.
/// The requirements this suite does not judge are listed with the reason (not_judged()).

#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "tests/conformance/sparkplug_view.hpp"

namespace eip2mqtt::test::conformance {

/// nullopt: the requirement holds; else what breaks it, and where.
using Verdict = std::optional<std::string>;

/// Which run of the conformance suite shows a requirement.
enum class Run {
    mqtt5,    ///< MQTT 5, two brokers, a primary host: the node's whole life
    mqtt311,  ///< MQTT 3.1.1: a birth and a clean stop
};

struct Requirement {
    std::string_view tck_id;
    Run run = Run::mqtt5;
    std::function<Verdict(const NodeView&)> check;
    /// Makes a view that satisfies check() one that does not.
    std::function<void(NodeView&)> break_it;
};

/// Every requirement the suite judges, in the specification's order.
std::span<const Requirement> edge_node_requirements();

struct NotJudged {
    std::string_view tck_id;
    std::string_view why;
};

/// The specification's tck-ids the suite does not judge (a host's, an MQTT server's, or beyond
/// what an edge node can show), each with the reason.
std::span<const NotJudged> not_judged();

}  // namespace eip2mqtt::test::conformance
