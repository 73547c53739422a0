#include "tests/support/chaos_rig.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <stdexcept>
#include <thread>

#include "eip2mqtt/core/plan/tag_type.hpp"
#include "tests/support/datagram_builder.hpp"
#include "tests/support/exchange_yaml.hpp"
#include "tests/support/forged_sender.hpp"
#include "tests/support/gateway_binary.hpp"

namespace eip2mqtt::test {
namespace {

using namespace std::chrono_literals;

constexpr const char* segment_address = "10.250.0.1";
constexpr std::uint16_t eip_port = 18246;

std::string unit_address(int unit) { return "10.250." + std::to_string(unit + 1) + ".2"; }
std::string segment_end(int unit) { return "10.250." + std::to_string(unit + 1) + ".1"; }

/// A UDP socket inside `ns`, bound to `address` and an ephemeral port; the port in `port`.
int bound_udp(const NetNamespace& ns, const std::string& address, std::uint16_t& port) {
    const int fd = ns.socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in where{};
    where.sin_family = AF_INET;
    ::inet_pton(AF_INET, address.c_str(), &where.sin_addr);
    socklen_t length = sizeof where;
    if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&where), sizeof where) != 0 ||
        ::getsockname(fd, reinterpret_cast<sockaddr*>(&where), &length) != 0) {
        throw std::runtime_error("cannot bind a UDP socket on " + address);
    }
    port = ntohs(where.sin_port);
    return fd;
}

/// The PLC's datagram `n`: COUNT = n and NOISE, both changing each time (so `_values` carries
/// both), its request id n.
std::vector<std::byte> counter_datagram(std::int64_t count) {
    using core::plan::TagType;
    return DatagramBuilder("10.0.0.2", 7, 8)
        .request_id(static_cast<std::uint16_t>(count))
        .set("0.0", TagType::dint, std::int64_t{count})
        .set("4.0", TagType::dint, std::int64_t{(count * 7919) % 1000003})
        .build();
}

}  // namespace

ChaosRig::ChaosRig(ChaosSettings settings)
    : settings_(settings),
      epoch_(Clock::now()),
      system_epoch_(std::chrono::system_clock::now()),
      segment_("seg"),
      broker_(MosquittoOptions{.persistence = true}) {
    segment_.run({"ip", "addr", "add", std::string(segment_address) + "/32", "dev", "lo"});
    for (int unit = 0; unit < 2; ++unit) {
        units_[unit] = std::make_unique<NetNamespace>("u" + std::to_string(unit));
        units_[unit]->link_to(segment_, unit_address(unit), segment_end(unit));
        proxies_[unit] =
            std::make_unique<TcpProxy>(broker_.port(), segment_.listen_tcp(segment_address));
    }
    recorder_ = std::make_unique<MqttRecorder>(broker_.url(),
                                               std::vector<std::string>{"test/#", "answers/#"});
    capture_ = std::make_unique<SegmentCapture>(bound_udp(segment_, segment_address, capture_port_),
                                                system_epoch_);
    for (int unit = 0; unit < 2; ++unit) start_unit(unit);
}

ChaosRig::~ChaosRig() {
    plc_.reset();
    for (auto& gateway : gateways_) {
        if (gateway) gateway->signal(SIGCONT);
    }
    if (broker_stopped_ && broker_.pid() > 0) ::kill(broker_.pid(), SIGCONT);
    gateways_ = {};
}

std::chrono::milliseconds ChaosRig::now() const {
    return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - epoch_);
}

namespace {

/// EIP2MQTT_CHAOS_LOG_LEVEL: the units' log level (`debug` to follow a seed); info by default.
std::string log_level() {
    const char* text = std::getenv("EIP2MQTT_CHAOS_LOG_LEVEL");
    return text != nullptr && *text != '\0' ? text : "info";
}

}  // namespace

std::string ChaosRig::unit_config(int unit) const {
    const auto& id = chaos_unit_ids[unit];
    const auto exchanges =
        ExchangeYaml::produce("sp", "10.1.2.3", 10,
                              std::string(segment_address) + ":" + std::to_string(capture_port_))
            .period_ms(static_cast<std::uint32_t>(settings_.produce_period.count()))
            .tag("SPEED_SP", "0.0", "real", "writable: true, initial: 3000")
            .str() +
        ExchangeYaml::consume("line", "10.0.0.2", 7)
            .length(8)
            .period_ms(static_cast<std::uint32_t>(settings_.consume_period.count()))
            .timeout_ms(0)
            .key("source", segment_address)
            .tag("COUNT", "0.0", "dint", "refresh_s: 3600")
            .tag("NOISE", "4.0", "dint", "refresh_s: 3600")
            .str();
    return "gateway: { id: " + id + ", state_dir: " + dir_.path() + "/" + id +
           ", log_level: " + log_level() +
           " }\n"
           "mqtt: { url: \"tcp://" +
           segment_address + ":" + std::to_string(proxies_[unit]->port()) +
           "\", base_topic: test, qos: 1, batch: true }\n"
           "eip: { bind: " +
           unit_address(unit) + ", port: " + std::to_string(eip_port) +
           " }\n"
           "redundancy: { pair: turbine, takeover_ms: " +
           std::to_string(settings_.takeover.count()) + " }\nexchanges:\n" + exchanges;
}

void ChaosRig::start_unit(int unit) {
    if (gateways_[unit]) earlier_logs_[unit] += gateways_[unit]->output() + "--- killed ---\n";
    const auto path = dir_.write(chaos_unit_ids[unit] + ".yaml", unit_config(unit));
    gateways_[unit] =
        std::make_unique<ChildProcess>(units_[unit]->inside({gateway_binary(), "run", "-c", path}));
}

std::string ChaosRig::settle() {
    const auto roles = [&](const std::vector<Received>& all) {
        std::array<std::string, 2> role;
        for (const auto& m : all) {
            for (int unit = 0; unit < 2; ++unit) {
                if (m.topic == "test/_gateway/" + chaos_unit_ids[unit] + "/role")
                    role[unit] = m.payload;
            }
        }
        return (role[0] == "leader" && role[1] == "standby") ||
               (role[0] == "standby" && role[1] == "leader");
    };
    if (!recorder_->wait_for(roles, 30s)) return "the pair never settled: one leader, one standby";
    return "";
}

void ChaosRig::run(const std::vector<ChaosFault>& schedule) {
    std::uint16_t plc_port = 0;
    const auto faults = [&](std::uint64_t seed) {
        fault_injector::FaultConfig c;
        c.seed = seed;
        c.loss = 0.02;
        c.duplicate = 0.02;
        c.reorder = 0.02;
        c.jitter = 0.02;
        c.jitter_delay = 3 * settings_.consume_period / 2;
        c.corrupt_byte = 0.02;
        c.corrupt_byte_offset = 32 + 5;  // NOISE only: COUNT names the sample
        return c;
    };
    plc_ = std::make_unique<FaultyPlc>(
        bound_udp(segment_, segment_address, plc_port),
        [](std::uint64_t n) { return counter_datagram(static_cast<std::int64_t>(n)); },
        std::vector<FaultyPlc::Destination>{
            {unit_address(0), eip_port, faults(settings_.seed * 2 + 1)},
            {unit_address(1), eip_port, faults(settings_.seed * 2 + 2)}},
        settings_.consume_period, epoch_);
    // Each fault's beginning and end, in time order (a fault of no length begins first).
    struct Step {
        std::chrono::milliseconds at;
        std::size_t fault;
        bool heal;
    };
    std::vector<Step> steps;
    for (std::size_t i = 0; i < schedule.size(); ++i) {
        steps.push_back({schedule[i].at, i, false});
        steps.push_back({schedule[i].at + schedule[i].length, i, true});
    }
    std::stable_sort(steps.begin(), steps.end(),
                     [](const Step& a, const Step& b) { return a.at < b.at; });
    begun_.assign(schedule.size(), std::chrono::milliseconds(0));
    auto start = Clock::now();
    std::size_t on = 0;  // faults begun and not healed
    for (const auto& step : steps) {
        write_until(start + step.at);
        step.heal ? heal(schedule[step.fault], step.fault)
                  : apply(schedule[step.fault], step.fault);
        on = step.heal ? on - 1 : on + 1;
        if (settings_.keep_quiet && on == 0) start = std::max(start, Clock::now() - step.at);
    }
    write_until(Clock::now() + 3 * settings_.takeover);
    excuse_both_down();
    finish();
}

void ChaosRig::forge() {
    ForgedSender sender(segment_.socket(AF_INET, SOCK_RAW, IPPROTO_RAW));
    // A hostile node's address, then each unit's: the exchange's `source` refuses them all.
    const std::array<std::string, 3> sources{"10.250.0.66", unit_address(0), unit_address(1)};
    for (int i = 0; i < 9; ++i) {
        const auto datagram = counter_datagram(1'000'000 + i);
        for (int unit = 0; unit < 2; ++unit) {
            sender.send(sources[i % 3], eip_port, unit_address(unit), eip_port, datagram);
        }
    }
}

void ChaosRig::write_until(Clock::time_point until) {
    // Bounded: one write per renewal interval (a quarter takeover) of the span, at most; none
    // while the recorder cannot.
    while (Clock::now() < until) {
        if (!broker_stopped_ && !broker_killed_ && recorder_->connected()) write();
        std::this_thread::sleep_until(std::min(until, Clock::now() + settings_.takeover / 4));
    }
}

void ChaosRig::write() {
    const auto id = "w" + std::to_string(++writes_made_);
    const double value = 1000 + writes_made_;
    writes_.push_back({id, value, now()});
    recorder_->publish_request("test/sp/SPEED_SP/set", std::to_string(writes_made_ + 1000),
                               "answers/chaos", id);
}

void ChaosRig::finish() {
    // Every write answered, or the bound passed (an unanswered one is then a violation).
    const auto answered = [&](const std::vector<Received>& all) {
        std::size_t n = 0;
        for (const auto& m : all) n += m.topic == "answers/chaos";
        return n >= writes_.size();
    };
    recorder_->wait_for(answered, 3 * settings_.takeover + 10s);
    plc_->stop();
    // Then every sample that must be published is, or the bound passed.
    const auto must = required();
    const auto all_published = [&](const std::vector<Received>& all) {
        std::set<std::int64_t> seen;
        for (const auto& p : published(all)) seen.insert(p.sample);
        return std::all_of(must.begin(), must.end(),
                           [&](std::int64_t n) { return seen.count(n) > 0; });
    };
    recorder_->wait_for(all_published, 2 * settings_.takeover + 10s);
    capture_->stop();
    end_ = now();
}

}  // namespace eip2mqtt::test
