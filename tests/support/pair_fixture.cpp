#include "tests/support/pair_fixture.hpp"

#include <signal.h>

#include <iostream>
#include <map>
#include <vector>

#include "tests/support/exchange_yaml.hpp"
#include "tests/support/free_port.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {

std::string PairTest::pair_config(const std::string& id, const std::string& broker_url,
                                  std::uint16_t port, std::uint32_t period_ms,
                                  const std::string& sections, const std::string& exchanges,
                                  const std::string& mqtt) const {
    return unit_config(
        id, broker_url, port,
        ExchangeYaml::produce("sp", "10.1.2.3", 10, "127.0.0.1:" + std::to_string(capture_.port()))
                .period_ms(period_ms)
                .tag("SPEED_SP", "0.0", "real", "writable: true, initial: 3000")
                .str() +
            exchanges,
        mqtt, sections);
}

std::string PairTest::unit_config(const std::string& id, const std::string& broker_url,
                                  std::uint16_t port, const std::string& exchanges,
                                  const std::string& mqtt, const std::string& sections) const {
    const auto url = broker_url.front() == '[' ? broker_url : "\"" + broker_url + "\"";
    return "gateway: { id: " + id + ", state_dir: " + dir_.path() + "/" + id +
           ", log_level: debug }\n"
           "mqtt: { url: " +
           url + ", base_topic: test, qos: 1, metrics_interval_s: 1" + mqtt +
           " }\n"
           "eip: { bind: 127.0.0.1, port: " +
           std::to_string(port) +
           " }\n"
           "redundancy: { pair: turbine, takeover_ms: 1000 }\n" +
           sections + "exchanges:\n" + exchanges;
}

void PairTest::start_units(
    const std::function<std::string(const std::string& id, std::uint16_t port)>& config) {
    for (const std::string id : {"gw-a", "gw-b"}) {
        ports_[id] = free_udp_port();
        start_unit(id, config(id, ports_[id]));
    }
}

void PairTest::start_unit(const std::string& id, const std::string& config) {
    const auto path = dir_.write(id + ".yaml", config);
    gateways_[id] = std::make_unique<ChildProcess>(
        std::vector<std::string>{gateway_binary(), "run", "-c", path});
}

bool PairTest::says(const std::string& id, const std::string& role, std::size_t from,
                    std::chrono::milliseconds wait) {
    return recorder_
        ->wait_for_message(
            role_topic(id), [&](const std::string& p) { return p == role; }, wait, from)
        .has_value();
}

std::string PairTest::leader_beside_standby() {
    std::string leader;
    recorder_->wait_for(
        [&](const std::vector<Received>& all) {
            std::map<std::string, std::string> last;  // unit -> the role it said last
            for (const auto& m : all) {
                for (const std::string id : {"gw-a", "gw-b"}) {
                    if (m.topic == role_topic(id)) last[id] = m.payload;
                }
            }
            for (const std::string id : {"gw-a", "gw-b"}) {
                if (last[id] == "leader" && last[other(id)] == "standby") leader = id;
            }
            return !leader.empty();
        },
        std::chrono::seconds(30));
    return leader;
}

void PairTest::TearDown() {
    for (auto& [id, gateway] : gateways_) {
        if (!gateway) continue;
        gateway->signal(SIGCONT);
        if (HasFailure()) std::cerr << "--- " << id << " ---\n" << gateway->output();
    }
    gateways_.clear();
    recorder_.reset();
    broker_.reset();
}

}  // namespace eip2mqtt::test
