#pragma once
/// A hot-standby pair under a seeded schedule of faults, for the chaos tests: two real gateways,
/// each in a network namespace of its own joined to the test's segment namespace by a veth pair,
/// reaching a real Mosquitto through a TcpProxy of its own; a faulty PLC on the segment sending a
/// consumed counter to both; a capture of what the pair produces; a recorder of every message;
/// writes with answers on a response topic. It records everything, then runs every checker of
/// tests/support/promises.hpp over it (docs/testing.md). The broker runs with persistence, as a
/// packaged Mosquitto does, but never autosaves within a run: when it is killed it comes back
/// without retained messages and sessions, which the pair must survive.
///
///   segment namespace: 10.250.0.1 (lo): PLC, capture, the units' broker proxies, forged sources
///   unit 0 namespace: 10.250.1.2, default route via 10.250.1.1 (the segment's end of the veth)
///   unit 1 namespace: 10.250.2.2, default route via 10.250.2.1
///   the test's own namespace: Mosquitto and the recorder on 127.0.0.1

#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tests/support/chaos_schedule.hpp"
#include "tests/support/child_process.hpp"
#include "tests/support/faulty_plc.hpp"
#include "tests/support/gateway_fixture.hpp"
#include "tests/support/mosquitto.hpp"
#include "tests/support/mqtt_recorder.hpp"
#include "tests/support/net_namespace.hpp"
#include "tests/support/promises.hpp"
#include "tests/support/segment_capture.hpp"
#include "tests/support/tcp_proxy.hpp"

namespace eip2mqtt::test {

/// The units' ids: unit 0 and unit 1.
inline const std::array<std::string, 2> chaos_unit_ids{"gw-a", "gw-b"};

struct ChaosSettings {
    std::uint64_t seed = 1;
    std::chrono::milliseconds duration{20000};  ///< of the schedule
    std::chrono::milliseconds takeover{1000};
    std::chrono::milliseconds produce_period{50};
    std::chrono::milliseconds consume_period{20};
    /// Keep each quiet spell whole: when the last fault of a group ends late (its heal waited
    /// for a leader's renewal, or a restart), the later faults move by as long. Schedule
    /// version 2's; version 1 runs as it always did (the next fault at its time).
    bool keep_quiet = false;
};

class ChaosRig {
public:
    /// Builds the namespaces, the broker, the proxies, the capture and the recorder, and starts
    /// both units. Throws when a piece cannot be made.
    explicit ChaosRig(ChaosSettings settings);
    ~ChaosRig();
    ChaosRig(const ChaosRig&) = delete;
    ChaosRig& operator=(const ChaosRig&) = delete;

    /// Waits for one unit to lead and the other to stand by; empty, or what did not happen.
    std::string settle();
    /// Runs the PLC and the schedule, with writes in between; ends with every fault healed,
    /// the writes answered (or the bound passed) and the last samples published.
    void run(const std::vector<ChaosFault>& schedule);
    /// Each checker's violations (promises::report's lines), by the checker's name: "one
    /// producer", "leadership present", "leader kept", "published was sent", "samples once, in
    /// order", "writes answered once".
    std::map<std::string, std::string> check() const;
    /// What happened (the faults as applied, the roles) and each unit's log, for a failure.
    std::string story() const;

private:
    using Clock = std::chrono::steady_clock;
    std::chrono::milliseconds now() const;
    std::string unit_config(int unit) const;
    void start_unit(int unit);
    /// Begins schedule fault `index`; heal() ends it (faults may overlap).
    void apply(const ChaosFault& fault, std::size_t index);
    void heal(const ChaosFault& fault, std::size_t index);
    /// SIGCONT (stop_broker) or started again on its port (kill_broker); returns once a leader
    /// renews its lease again, with the time the broker was back.
    std::chrono::milliseconds restore_broker(ChaosKind kind);
    /// Adds to `unreachable_` the spans when both units were down at once.
    void excuse_both_down();
    /// SIGKILL, then the unit started again; returns once it says its role.
    void kill_and_restart(int unit);
    void forge();
    /// Writes every 250 ms until `until` (none while the broker is stopped).
    void write_until(Clock::time_point until);
    void write();
    void finish();

    std::vector<promises::Produced> produced() const;
    std::vector<promises::Sent> sent() const;
    std::vector<std::int64_t> required() const;
    /// The samples on `_values` and `_history` among `messages`.
    std::vector<promises::Published> published(const std::vector<Received>& messages) const;

    ChaosSettings settings_;
    Clock::time_point epoch_;
    std::chrono::system_clock::time_point system_epoch_;
    TempDir dir_;
    NetNamespace segment_;
    std::array<std::unique_ptr<NetNamespace>, 2> units_;
    Mosquitto broker_;
    std::unique_ptr<MqttRecorder> recorder_;
    std::array<std::unique_ptr<TcpProxy>, 2> proxies_;
    std::unique_ptr<SegmentCapture> capture_;
    std::uint16_t capture_port_ = 0;
    std::unique_ptr<FaultyPlc> plc_;
    std::array<std::unique_ptr<ChildProcess>, 2> gateways_;
    std::array<std::string, 2> earlier_logs_;  ///< of the processes killed
    bool broker_stopped_ = false;              ///< SIGSTOPped
    bool broker_killed_ = false;               ///< killed, not yet started again
    int writes_made_ = 0;
    std::chrono::milliseconds end_{0};

    std::vector<promises::Write> writes_;
    std::vector<promises::Span> disrupted_;          ///< broker paths down (QoS 1 repeats excused)
    std::vector<promises::Span> unreachable_;        ///< no unit could reach the broker
    std::vector<promises::Span> broker_lost_;        ///< Mosquitto killed, until back
    std::vector<promises::UnitFault> units_killed_;  ///< a unit killed, until restarted
    std::vector<promises::Span> faulted_;            ///< every fault, for the required samples
    std::vector<promises::UnitFault> unit_faults_;   ///< by unit ("": the broker's)
    std::array<std::vector<promises::Span>, 2> down_;  ///< a unit's path or process down
    std::vector<std::chrono::milliseconds> begun_;     ///< each schedule fault's start
    std::vector<std::string> story_;
};

}  // namespace eip2mqtt::test
