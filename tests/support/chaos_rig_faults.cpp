// ChaosRig's faults: each begun and healed as the schedule says, and what the checkers must
// know of it recorded (the spans a path was down, a unit was away, no unit could lead).

#include <signal.h>

#include <algorithm>

#include "tests/support/chaos_rig.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

bool of_broker(ChaosKind kind) {
    return kind == ChaosKind::stop_broker || kind == ChaosKind::kill_broker;
}

/// The kinds that take a unit away from the lease: its broker path down, or its process.
bool takes_unit_away(ChaosKind kind) {
    return kind == ChaosKind::cut_unit || kind == ChaosKind::cut_broker ||
           kind == ChaosKind::stall_broker || kind == ChaosKind::stop_unit ||
           kind == ChaosKind::kill_unit;
}

}  // namespace

void ChaosRig::apply(const ChaosFault& fault, std::size_t index) {
    story_.push_back(std::to_string(now().count()) + " ms: " + fault.str());
    begun_[index] = now();
    auto& proxy = *proxies_[fault.unit];
    using D = TcpProxy::Direction;
    switch (fault.kind) {
        case ChaosKind::cut_unit:
            units_[fault.unit]->cut(false);
            break;
        case ChaosKind::cut_broker:
            units_[fault.unit]->cut(true);
            break;
        case ChaosKind::stall_broker:
            proxy.set_mode(D::to_server, TcpProxy::Mode::stall);
            proxy.set_mode(D::to_client, TcpProxy::Mode::stall);
            break;
        case ChaosKind::delay_broker:
            proxy.set_delay(D::to_server, fault.delay);
            proxy.set_delay(D::to_client, fault.delay);
            break;
        case ChaosKind::stop_unit:
            gateways_[fault.unit]->signal(SIGSTOP);
            break;
        case ChaosKind::kill_unit:
            kill_and_restart(fault.unit);
            break;
        case ChaosKind::stop_broker:
            broker_stopped_ = true;
            ::kill(broker_.pid(), SIGSTOP);
            break;
        case ChaosKind::kill_broker:
            broker_killed_ = true;
            broker_.kill();
            break;
        case ChaosKind::forge:
            forge();
            break;
    }
}

void ChaosRig::heal(const ChaosFault& fault, std::size_t index) {
    auto path_back = now();  // when the broker paths are whole again
    auto& proxy = *proxies_[fault.unit];
    using D = TcpProxy::Direction;
    switch (fault.kind) {
        case ChaosKind::cut_unit:
        case ChaosKind::cut_broker:
            units_[fault.unit]->heal();
            break;
        case ChaosKind::stall_broker:
            proxy.set_mode(D::to_server, TcpProxy::Mode::pass);
            proxy.set_mode(D::to_client, TcpProxy::Mode::pass);
            break;
        case ChaosKind::delay_broker:
            proxy.set_delay(D::to_server, 0ms);
            proxy.set_delay(D::to_client, 0ms);
            break;
        case ChaosKind::stop_unit:
            gateways_[fault.unit]->signal(SIGCONT);
            break;
        case ChaosKind::stop_broker:
        case ChaosKind::kill_broker:
            path_back = restore_broker(fault.kind);
            break;
        case ChaosKind::kill_unit:
        case ChaosKind::forge:
            break;
    }
    const promises::Span span{begun_[index], now()};
    story_.push_back(std::to_string(span.to.count()) + " ms: healed " + to_string(fault.kind));
    if (fault.kind == ChaosKind::forge) return;  // it must change nothing
    faulted_.push_back(span);
    const bool path_down =
        fault.kind != ChaosKind::delay_broker && fault.kind != ChaosKind::kill_unit;
    if (path_down) disrupted_.push_back({span.from, path_back});
    if (of_broker(fault.kind)) unreachable_.push_back(span);
    if (fault.kind == ChaosKind::kill_broker) broker_lost_.push_back(span);
    if (fault.kind == ChaosKind::kill_unit)
        units_killed_.push_back({chaos_unit_ids[fault.unit], span});
    if (takes_unit_away(fault.kind)) down_[fault.unit].push_back(span);
    unit_faults_.push_back({of_broker(fault.kind) ? "" : chaos_unit_ids[fault.unit], span});
}

std::chrono::milliseconds ChaosRig::restore_broker(ChaosKind kind) {
    const auto from = recorder_->count();
    if (kind == ChaosKind::stop_broker) {
        ::kill(broker_.pid(), SIGCONT);
    } else {
        broker_.start();  // the same port: the proxies' upstream stays valid
    }
    broker_stopped_ = false;
    broker_killed_ = false;
    const auto back = now();
    // The units reconnect with their backoff (it grew while the broker did not answer), then one
    // claims the lead: the fault lasts until a leader renews again (docs/testing.md). After a
    // kill the recorder too reconnects and subscribes again first.
    const auto renewal = [](const std::string& p) {
        return p.find("\"claim\"") == std::string::npos && p.find("\"id\"") != std::string::npos;
    };
    recorder_->wait_for_message("test/_gateway/_pair/turbine/leader", renewal, 60s, from);
    return back;
}

void ChaosRig::kill_and_restart(int unit) {
    gateways_[unit]->signal(SIGKILL);
    gateways_[unit]->wait(10s);
    const auto from = recorder_->count();
    start_unit(unit);
    // Back once it says its role again (it consumes from then on): the fault's span ends there.
    const auto role = "test/_gateway/" + chaos_unit_ids[unit] + "/role";
    recorder_->wait_for_message(role, nullptr, 30s, from);
}

void ChaosRig::excuse_both_down() {
    // Overlapping faults may take both units away at once: no unit can lead then.
    for (const auto& a : down_[0]) {
        for (const auto& b : down_[1]) {
            const auto from = std::max(a.from, b.from);
            const auto to = std::min(a.to, b.to);
            if (from < to) unreachable_.push_back({from, to});
        }
    }
}

}  // namespace eip2mqtt::test
