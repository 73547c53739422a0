// The simulator drives a gateway: values of every type flow and change.

#include <csignal>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/gateway_binary.hpp"
#include "tests/support/gateway_fixture.hpp"

namespace eip2mqtt::test {
namespace EIP2MQTT_THIS_FILE {

const std::string sim_exchange = ExchangeYaml::consume("sim", "10.0.0.9", 3)
                                     .period_ms(20)
                                     .tag("B", "0.0", "bit")
                                     .tag("U8", "1.0", "byte")
                                     .tag("I16", "2.0", "int")
                                     .tag("U16", "4.0", "word")
                                     .tag("I32", "6.0", "dint")
                                     .tag("U32", "10.0", "udint")
                                     .tag("F32", "14.0", "real")
                                     .tag("I64", "18.0", "lint")
                                     .tag("F64", "26.0", "lreal")
                                     .str();

class SimulatorTest : public GatewayTest {};

TEST_F(SimulatorTest, SimulatedValuesOfEveryTypeFlowAndChange) {
    start(sim_exchange);
    ChildProcess sim({gateway_binary(), "sim", "-c", config_path_, "--duration", "20"});
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

}  // namespace EIP2MQTT_THIS_FILE
}  // namespace eip2mqtt::test
