#pragma once
/// What the hot-standby tests share: two units of one pair (`gw-a`, `gw-b`) on one real
/// Mosquitto, each producing exchange `sp` (SPEED_SP, a writable real) to the test's socket,
/// and the questions they ask of the role topics. A test starts the units itself, since where
/// each reaches the broker and listens differs from test to test.

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "tests/support/child_process.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/udp_client.hpp"

namespace eip2mqtt::test {

class PairTest : public ::testing::Test {
protected:
    static std::string role_topic(const std::string& id) { return "test/_gateway/" + id + "/role"; }
    static std::string other(const std::string& id) { return id == "gw-a" ? "gw-b" : "gw-a"; }

    /// Unit `id`'s configuration: the broker at `broker_url`, EIP on `port`, the produced
    /// exchange every `period_ms`; `sections` (YAML sections, `sparkplug:` say), `exchanges`
    /// (more of them, as ExchangeYaml writes them) and `mqtt` (as unit_config takes it) added.
    std::string pair_config(const std::string& id, const std::string& broker_url,
                            std::uint16_t port, std::uint32_t period_ms,
                            const std::string& sections = "", const std::string& exchanges = "",
                            const std::string& mqtt = "") const;
    /// A unit's configuration with `exchanges` alone (items of the list, ExchangeYaml), `mqtt`
    /// (more keys of the `mqtt:` flow mapping: ", batch: true") and `sections`. `broker_url`
    /// is one URL, or a YAML flow list of them (`[ "tcp://...", ... ]`).
    std::string unit_config(const std::string& id, const std::string& broker_url,
                            std::uint16_t port, const std::string& exchanges,
                            const std::string& mqtt = "", const std::string& sections = "") const;
    /// Writes `id`'s configuration and runs the unit on it.
    void start_unit(const std::string& id, const std::string& config);
    /// Both units, each on an EIP port of its own (ports_), on the configuration `config`
    /// makes of its id and that port.
    void start_units(
        const std::function<std::string(const std::string& id, std::uint16_t port)>& config);
    /// Waits for `id` to say `role` on its role topic (after message `from`).
    bool says(const std::string& id, const std::string& role, std::size_t from = 0,
              std::chrono::milliseconds wait = std::chrono::seconds(30));
    /// The unit that said `leader` last while the other said `standby` last: the pair as it
    /// stands, not merely the first to lead, since a unit stalled on a loaded machine can lose
    /// its first lease to the other. Empty when the pair did not get there.
    std::string leader_beside_standby();
    /// Shows each unit's log when the test failed; resumes a stopped one so it can end.
    void TearDown() override;

    TempDir dir_;
    UdpClient capture_;
    std::unique_ptr<Mosquitto> broker_;
    std::unique_ptr<MqttRecorder> recorder_;
    std::map<std::string, std::unique_ptr<ChildProcess>> gateways_;
    std::map<std::string, std::uint16_t> ports_;  ///< each unit's EIP port (start_units)
};

}  // namespace eip2mqtt::test
