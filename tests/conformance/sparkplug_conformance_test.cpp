// The Sparkplug B 3.0 conformance of the edge node, judged from outside: the real binary behind
// two recording relays, the suite as its primary host and its plant. One run of the node's whole
// life (MQTT 5, two brokers): births after the host's STATE (an older one and another host's
// ignored), DATA, rebirth requests with and without datatype, DCMD by name and by alias alone,
// an offline STATE older than the last online one, a device that goes silent and returns, the
// host offline (the node leaves for the second broker), a clean stop and a restart. Then every
// requirement of sparkplug_requirements.cpp is judged over what the relays saw, and each check
// is seen to fail on the same recording altered to break it; Eclipse Tahu decodes every payload.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/conformance/sparkplug_connection_checks.hpp"
#include "tests/conformance/sparkplug_requirements.hpp"
#include "tests/conformance/sparkplug_run.hpp"
#include "tests/support/tahu.hpp"

namespace eip2mqtt::test::conformance {
namespace EIP2MQTT_THIS_FILE {

using namespace std::chrono_literals;
using nlohmann::json;

/// Every requirement of `run` holds over `view`, and fails once altered.
void judge(Run run, const NodeView& view) {
    std::size_t judged = 0;
    for (const auto& requirement : edge_node_requirements()) {
        if (requirement.run != run) continue;
        ++judged;
        const auto verdict = requirement.check(view);
        EXPECT_FALSE(verdict.has_value()) << requirement.tck_id << ": " << *verdict;
        auto altered = view;
        try {
            requirement.break_it(altered);
        } catch (const std::exception& e) {
            ADD_FAILURE() << requirement.tck_id << ": cannot be altered: " << e.what();
            continue;
        }
        EXPECT_TRUE(requirement.check(altered).has_value())
            << requirement.tck_id << ": its check did not fail on a recording altered to break it";
    }
    EXPECT_GT(judged, 0u);
}

/// Eclipse Tahu's decoder reads every payload the node published, and every will.
void expect_tahu_reads_every_payload(const SparkplugRun& run) {
    const auto payloads = run.payloads();
    ASSERT_FALSE(payloads.empty());
    const auto decoded = tahu_decode_all(payloads);
    ASSERT_EQ(decoded.size(), payloads.size());
    for (const auto& payload : decoded) EXPECT_TRUE(payload.contains("metrics")) << payload;
}

/// The alias of `name` in the last DBIRTH of setpoints.
std::uint64_t alias_in_birth(const NodeView& view, const std::string& name) {
    std::uint64_t alias = 0;
    for (const auto& c : view.connections) {
        for (const auto& p : c.packets) {
            if (!p.from_node || p.packet.topic != view.topic("DBIRTH") + "/setpoints") continue;
            if (const auto* m = metric_named(*p.payload, name)) alias = m->alias();
        }
    }
    return alias;
}

void host_and_commands(SparkplugRun& run) {
    // Broker 0's host was offline; an older online STATE is ignored, a newer one brings births.
    ASSERT_TRUE(run.subscribed_to_state(0, 1)) << run.output();
    run.state(0, true, 90);
    run.state(0, true, 110);
    ASSERT_TRUE(run.sent("NBIRTH", 1)) << run.output();
    ASSERT_TRUE(run.sent("DBIRTH", 2)) << run.output();  // line and setpoints
    ASSERT_TRUE(run.sent("NDATA", 1)) << run.output();
    // A rebirth at once, then one without datatype within the hold: DATA stops until it.
    run.rebirth(0, true);
    ASSERT_TRUE(run.sent("NBIRTH", 2)) << run.output();
    run.rebirth(0, false);
    ASSERT_TRUE(run.sent("NBIRTH", 3)) << run.output();
    // Writes: SP by name with its datatype, SPR by alias alone.
    const json sp{{"name", "SP"}, {"type", "Int32"}, {"value", 42}};
    run.dcmd(0, tahu_encode({{"timestamp", 1}, {"metrics", json::array({sp})}}));
    ASSERT_TRUE(run.produced([](std::int32_t sp, float) { return sp == 42; })) << run.output();
    SparkplugPayload by_alias;
    by_alias.set_timestamp(1);
    auto& m = *by_alias.add_metrics();
    m.set_alias(alias_in_birth(run.view(), "SPR"));
    m.set_float_value(2.5f);
    run.dcmd(0, by_alias.SerializeAsString());
    ASSERT_TRUE(run.produced([](std::int32_t, float spr) { return spr == 2.5f; })) << run.output();
    // An offline STATE older than the online one: the node stays, its DATA goes on.
    const auto before = run.count_sent(0, "DDATA");
    run.state(0, false, 105);
    ASSERT_TRUE(run.sent("DDATA", before + 3, 0)) << run.output();
}

void plant_and_walk(SparkplugRun& run) {
    const auto births = run.count_sent(2, "DBIRTH");
    run.mark("line silent");
    run.silence_plant(true);
    ASSERT_TRUE(run.sent("DDEATH", 1)) << run.output();
    run.mark("line back");
    run.silence_plant(false);
    ASSERT_TRUE(run.sent("DBIRTH", births + 1)) << run.output();
    // The host offline on broker 0, where the node is born: it leaves for broker 1, where the
    // host's retained STATE says offline; births once a newer online one comes.
    run.state(1, false, 200);
    run.state(0, false, 120);
    ASSERT_TRUE(run.subscribed_to_state(1, 1)) << run.output();
    run.state(1, true, 190);
    run.state(1, true, 210);
    ASSERT_TRUE(run.sent("NBIRTH", 1, 1)) << run.output();
    ASSERT_TRUE(run.sent("DDATA", 1, 1)) << run.output();
}

TEST(SparkplugConformance, Mqtt5TheNodesWholeLifeHoldsEveryRequirement) {
    SparkplugRun run(5, true);
    run.state(0, false, 100);
    run.start_gateway();
    host_and_commands(run);
    if (HasFatalFailure()) return;
    plant_and_walk(run);
    if (HasFatalFailure()) return;
    EXPECT_EQ(run.stop_gateway(), 0) << run.output();
    // A restart: the first broker again, the bdSeq on from the last process's.
    run.start_gateway();
    ASSERT_TRUE(run.subscribed_to_state(0, 2)) << run.output();
    run.state(0, true, 300);
    ASSERT_TRUE(run.sent("NBIRTH", 4, 0)) << run.output();
    EXPECT_EQ(run.stop_gateway(), 0) << run.output();

    judge(Run::mqtt5, run.view());
    expect_tahu_reads_every_payload(run);
}

TEST(SparkplugConformance, Mqtt311ACleanStopSaysTheNdeathBeforeItsDisconnect) {
    SparkplugRun run(3, false);
    run.start_gateway();
    ASSERT_TRUE(run.sent("NBIRTH", 1)) << run.output();
    ASSERT_TRUE(run.sent("DBIRTH", 1)) << run.output();
    EXPECT_EQ(run.stop_gateway(), 0) << run.output();
    const auto view = run.view();
    ASSERT_FALSE(view.connections.empty());
    EXPECT_EQ(view.connections.front().connect.protocol_level, 4);
    judge(Run::mqtt311, view);
    expect_tahu_reads_every_payload(run);
}

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test::conformance
