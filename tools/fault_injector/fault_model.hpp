#pragma once
/// The decisions of the fault injector, without sockets or clocks: which datagrams are lost,
/// delayed, duplicated, held back for reordering, truncated or corrupted, and how. Seeded and
/// deterministic: the same seed and the same datagrams give the same decisions, and each fault
/// draws from its own random stream, so enabling one fault never changes another's decisions.
/// Used by the `eip2mqtt-fault-injector` proxy and, in-process, by the soak test.

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::fault_injector {

/// Header fields --corrupt-field can change (docs/protocol.md §2).
enum class HeaderField : std::uint8_t {
    type,       ///< byte 0
    version,    ///< byte 1
    rid,        ///< bytes 2-3
    producer,   ///< bytes 4-7
    exchange,   ///< bytes 8-11
    time,       ///< bytes 12-15 (seconds)
    status,     ///< bytes 20-23
    signature,  ///< bytes 24-27
    reserved,   ///< bytes 28-31
};

std::optional<HeaderField> parse_header_field(std::string_view name);
std::string_view to_string(HeaderField field);

/// The faults, in the order they are applied to a datagram and reported.
enum class Fault : std::uint8_t {
    loss,
    corrupt_field,
    corrupt_byte,
    corrupt_bit,
    truncate,
    duplicate,
    delay,
    jitter,
    reorder,
};
inline constexpr std::size_t fault_count = 9;
std::string_view to_string(Fault fault);

/// What to inject. Probabilities are 0..1; offsets out of a datagram's range are replaced by a
/// random one. Defaults inject nothing: the proxy then forwards every datagram unchanged.
struct FaultConfig {
    std::uint64_t seed = 1;
    double loss = 0;
    unsigned loss_burst = 1;  ///< datagrams lost in a row once a loss starts (>= 1)
    std::chrono::milliseconds delay{0};
    double jitter = 0;  ///< probability of an extra `jitter_delay`
    std::chrono::milliseconds jitter_delay{0};
    double duplicate = 0;
    double reorder = 0;  ///< hold the datagram and send it after the next one
    double truncate = 0;
    std::optional<std::size_t> truncate_length;  ///< cut to this length; random when unset
    double corrupt_byte = 0;
    std::optional<std::size_t> corrupt_byte_offset;
    double corrupt_bit = 0;
    std::optional<std::size_t> corrupt_bit_offset;  ///< bit index: byte * 8 + bit (0 = LSB)
    double corrupt_field = 0;
    HeaderField field = HeaderField::type;

    /// Configured probability of each fault, for the report (delay: 1 when set, else 0).
    double probability(Fault fault) const;
};

/// Applies one command-line option (`--loss` as "loss", its value "0.1") to `config`; an error
/// message names the option and what was expected.
core::Result<bool, std::string> apply_option(FaultConfig& config, std::string_view name,
                                             std::string_view value);

/// A datagram to send, `delay` after the datagram that produced it arrived.
struct Emission {
    std::vector<std::byte> bytes;
    std::chrono::milliseconds delay{0};
};

struct FaultCounters {
    std::uint64_t in = 0;
    std::uint64_t out = 0;                              ///< emissions returned
    std::array<std::uint64_t, fault_count> affected{};  ///< datagrams each fault changed

    std::uint64_t of(Fault fault) const { return affected[static_cast<std::size_t>(fault)]; }
};

/// Deterministic 64-bit generator (SplitMix64): the same sequence on every platform, unlike the
/// distributions of <random>.
class Rng {
public:
    explicit Rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next();
    /// Uniform in [0, 1).
    double uniform();
    /// Uniform in [0, bound); bound > 0.
    std::uint64_t below(std::uint64_t bound);
    /// True with probability `p`.
    bool chance(double p) { return uniform() < p; }

private:
    std::uint64_t state_;
};

class FaultModel {
public:
    explicit FaultModel(const FaultConfig& config);

    /// Decides the fate of one received datagram; returns what to send now or later, in order
    /// (empty when it is lost or held for reordering). A held datagram is released, with the
    /// delay of the releasing one, right after the next datagram that is not lost.
    std::vector<Emission> on_datagram(std::vector<std::byte> datagram);

    /// Releases a held datagram at the end (not counted as reordered); empty if none.
    std::vector<Emission> flush();

    bool holding() const { return !held_.empty(); }
    const FaultCounters& counters() const { return counters_; }
    const FaultConfig& config() const { return config_; }

private:
    Rng& rng(Fault fault) { return rngs_[static_cast<std::size_t>(fault)]; }
    void count(Fault fault) { ++counters_.affected[static_cast<std::size_t>(fault)]; }
    bool corrupt_field(std::vector<std::byte>& bytes);
    bool corrupt_byte(std::vector<std::byte>& bytes);
    bool corrupt_bit(std::vector<std::byte>& bytes);
    bool truncate(std::vector<std::byte>& bytes);

    FaultConfig config_;
    std::vector<Rng> rngs_;
    unsigned burst_left_ = 0;
    std::vector<Emission> held_;
    FaultCounters counters_;
};

/// The report printed at the end: datagrams in and out, and per fault the affected count next
/// to the configured probability.
std::string format_report(const FaultModel& model, double seconds);
std::string format_report_json(const FaultModel& model, double seconds);

}  // namespace eip2mqtt::fault_injector
