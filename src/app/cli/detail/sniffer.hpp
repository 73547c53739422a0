#pragma once
/// The parts of `sniff` (sniff.cpp): what it makes of each datagram it hears (a line, the
/// sequence of its exchange, arrival statistics), the tables it prints, and the set-up it takes
/// from its options. The Sniffer reads the time through the clock it is given.

#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/adapters/udp/multicast.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/core/clock.hpp"
#include "eip2mqtt/core/exchange/arrival_stats.hpp"
#include "eip2mqtt/core/exchange/wire_survey.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/network_load.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app::detail {

/// One exchange seen on the wire, configured or not.
struct SniffedExchange {
    std::string label;                               ///< configured name, else producer/exchange
    const core::plan::ExchangePlan* plan = nullptr;  ///< nullptr when not configured
    core::exchange::ArrivalStats arrivals;
    bool synchronised = false;
    std::uint16_t last_rid = 0;
    std::uint64_t received = 0;
    std::uint64_t missed = 0;
    std::uint64_t duplicates = 0;
    std::uint64_t out_of_order = 0;
    /// With --yaml, for an exchange the configuration lacks: what its skeleton says.
    std::optional<core::exchange::WireSurvey> survey;
};

/// What --yaml needs besides the datagrams: the local broadcast addresses (to tell a
/// subnet-directed broadcast) and the tolerance of a synced producer clock.
struct YamlSettings {
    std::vector<std::uint32_t> broadcast_addresses;
    std::chrono::milliseconds clock_tolerance{2000};
};

/// What became of a datagram under docs/protocol.md §4 rule 6.
enum class Sequence { sample, duplicate, out_of_order };

/// §4 rule 6: d = (rid - last) mod 65536; 0 duplicate, 1..32767 new sample (d - 1 missed),
/// >= 32768 late or reordered. The first datagram, and with a configuration the first after a
/// silence longer than the exchange's timeout, resynchronises without counting.
Sequence apply_sequence(SniffedExchange& exchange, std::uint16_t rid, core::MonoTime now);

/// Local wall time as tcpdump prints it: HH:MM:SS.uuuuuu.
std::string local_time(core::WallTime now);

/// The producer's time stamp in UTC (ISO 8601), or `none` for 0.
std::string producer_time(const core::wire::Header& header);

class Sniffer {
public:
    /// `yaml`: gather the skeletons of unconfigured exchanges (print_skeleton). `clock` must
    /// outlive the sniffer.
    Sniffer(std::ostream& out, std::vector<core::plan::ExchangePlan> plans,
            std::chrono::nanoseconds interval, std::optional<YamlSettings> yaml,
            const core::Clock& clock);

    /// `destination`: the address the datagram was sent to (0: unknown).
    void on_datagram(std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
                     std::uint32_t destination);

    /// The per-exchange table, rates over the last interval; `fragments`: IP fragments the
    /// capture saw and could not decode; `kernel_drops`: frames the capture was too slow for.
    void print_statistics(std::uint64_t fragments, std::uint64_t kernel_drops);

    /// With --yaml: the skeleton of every exchange seen that the configuration lacks.
    void print_skeleton();

private:
    /// Datagrams seen, and the bytes they take on an Ethernet link.
    struct WireTotals {
        std::uint64_t datagrams = 0;
        std::uint64_t bytes = 0;
    };

    /// With a configuration: the load measured since the last table beside the one the
    /// configuration puts on the link, every datagram counted as Ethernet carries it.
    void print_load(core::MonoTime now);
    SniffedExchange& find_or_add(const core::wire::ExchangeKey& key);

    std::ostream& out_;
    const core::Clock& clock_;
    std::vector<core::plan::ExchangePlan> plans_;  ///< never resized: exchanges_ points into it
    core::plan::Rate configured_;
    WireTotals wire_;
    WireTotals window_;  ///< wire_ at the last table
    core::MonoTime window_start_;
    std::chrono::nanoseconds interval_;
    std::optional<YamlSettings> yaml_;
    std::vector<SniffedExchange> exchanges_;  ///< in order of first sight
    std::map<core::wire::ExchangeKey, std::size_t> index_;
    std::map<core::wire::DropReason, std::uint64_t> dropped_;
};

/// What sniff takes from its options and configuration.
struct SniffSetup {
    std::uint16_t port = 18246;
    std::vector<core::plan::ExchangePlan> plans;
    std::vector<adapters::udp::MulticastMembership> groups;
    std::optional<YamlSettings> yaml;
};

/// nullopt when the configuration does not load (its errors printed on `err`).
std::optional<SniffSetup> load_setup(const SniffOptions& options, std::ostream& err);

}  // namespace eip2mqtt::app::detail
