#pragma once
/// What the wire shows of one exchange nobody has configured yet (`sniff --yaml`):
/// its length, signature, period, destination and producer clock, gathered datagram by datagram
/// into a summary that adapters::yaml::yaml_skeleton turns into configuration. Pure: receive
/// times and destinations are passed in.
///
/// The period is measured from receive times and request ids: the time from the first to the
/// last datagram taken as a sample, divided by the request-id steps between them. A lost
/// datagram still counts as a period (its request id was skipped); a duplicate, or a datagram
/// whose request id is behind the last (late, reordered), counts for nothing; two in sequence
/// behind it are a producer that restarted, measured on from there.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>

#include "eip2mqtt/core/enum_names.hpp"
#include "eip2mqtt/core/exchange/remote_producer_clock.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::exchange {

/// How a datagram was addressed.
enum class DestinationKind : std::uint8_t {
    unknown,    ///< the receiving socket did not say
    unicast,    ///< to one host
    broadcast,  ///< 255.255.255.255 or a subnet's broadcast address
    multicast,  ///< to a group, 224.0.0.0/4
};

inline constexpr auto destination_kind_names =
    enum_names<DestinationKind>("unknown", "unicast", "broadcast", "multicast");

constexpr std::string_view to_string(DestinationKind kind) {
    return destination_kind_names.name_of(kind);
}

struct Destination {
    DestinationKind kind = DestinationKind::unknown;
    std::uint32_t address = 0;  ///< IPv4, host byte order; 0 when unknown
    friend bool operator==(const Destination&, const Destination&) = default;
};

/// Classifies a datagram's destination address (host byte order; 0: unknown). A broadcast to a
/// subnet looks like any address, so `broadcast_addresses` lists those of the local interfaces.
Destination classify_destination(std::uint32_t address,
                                 std::span<const std::uint32_t> broadcast_addresses);

/// What was seen of one exchange. Where datagrams disagreed, the last one's is kept and the
/// disagreement flagged.
struct WireSummary {
    wire::ExchangeKey key;
    std::uint64_t datagrams = 0;
    std::uint16_t length = 0;  ///< data bytes of the last datagram
    std::uint16_t min_length = 0;
    std::uint16_t max_length = 0;
    wire::Signature signature;  ///< the last datagram's
    bool signature_varied = false;
    /// Mean period in ms (see the file comment); nullopt until two datagrams are a step apart.
    std::optional<double> period_ms;
    std::uint64_t period_steps = 0;  ///< request-id steps it was measured over
    Destination destination;         ///< the last datagram's
    bool destination_varied = false;
    ClockState clock = ClockState::none;          ///< the last datagram's
    std::optional<std::int64_t> clock_offset_ms;  ///< producer minus receive time, last stamped
    bool clock_varied = false;
    std::chrono::milliseconds clock_tolerance{2000};

    friend bool operator==(const WireSummary&, const WireSummary&) = default;
};

class WireSurvey {
public:
    /// `clock_tolerance`: how far the producer's time may be from the receive time and be
    /// `synced` (the gateway's default, 2000 ms).
    explicit WireSurvey(wire::ExchangeKey key,
                        std::chrono::milliseconds clock_tolerance = std::chrono::seconds(2));

    /// One datagram of the exchange: its header, `data_length` data bytes, its destination,
    /// received at `now` (monotonic) and `receive_ms` (ms since 1970 UTC).
    void on_datagram(const wire::Header& header, std::size_t data_length,
                     const Destination& destination, MonoTime now, std::int64_t receive_ms);

    const WireSummary& summary() const { return summary_; }

private:
    struct Sample {
        std::uint16_t rid = 0;
        MonoTime time{};
    };
    /// Adds `step` request ids from `from` to `now` to the measurement; `now` is the new last.
    void measure(const Sample& from, std::uint16_t step, MonoTime now);

    WireSummary summary_;
    RemoteProducerClock clock_;
    std::optional<Sample> last_;            ///< the last sample
    std::optional<Sample> behind_;          ///< the last datagram behind it, if the last seen was
    std::chrono::nanoseconds measured_{0};  ///< time over summary_.period_steps
};

}  // namespace eip2mqtt::core::exchange
