// The simulator drives a gateway: values of every type flow and change.

#include <csignal>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace {

const std::string sim_exchange = R"(  - name: sim
    direction: consume
    producer_id: 10.0.0.9
    exchange_id: 3
    period_ms: 20
    topic: sim
    tags:
      - { name: B, address: "0.0", type: bit }
      - { name: U8, address: "1.0", type: byte }
      - { name: I16, address: "2.0", type: int }
      - { name: U16, address: "4.0", type: word }
      - { name: I32, address: "6.0", type: dint }
      - { name: U32, address: "10.0", type: udint }
      - { name: F32, address: "14.0", type: real }
      - { name: I64, address: "18.0", type: lint }
      - { name: F64, address: "26.0", type: lreal }
)";

class SimulatorTest : public GatewayTest {};

TEST_F(SimulatorTest, SimulatedValuesOfEveryTypeFlowAndChange) {
    start(sim_exchange);
    ChildProcess sim({EIP2MQTT_BINARY, "sim", "-c", config_path_, "--duration", "20"});
    for (const auto* tag : {"B", "U8", "I16", "U16", "I32", "U32", "F32", "I64", "F64"}) {
        const std::string t = topic(std::string("sim/") + tag);
        // At least two distinct values: the simulator changes them.
        EXPECT_TRUE(recorder_->wait_for([&](const std::vector<Received>& all) {
            std::set<std::string> values;
            for (const auto& m : all) {
                if (m.topic == t) values.insert(nlohmann::json::parse(m.payload)["value"].dump());
            }
            return values.size() >= 2;
        })) << tag;
    }
    expect_field(topic("sim/_status"), "state", "\"ok\"");
    sim.signal(SIGTERM);
    EXPECT_EQ(sim.wait(std::chrono::seconds(5)), 0);
}

}  // namespace
}  // namespace eip2mqtt::test
