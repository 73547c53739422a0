// `eip2mqtt sniff`: a live decoder for the field. Prints every datagram's header (and, given a
// configuration, its tags), then per-exchange arrival statistics at each interval, so that an
// engineer can see what a producer really sends before configuring the gateway for it. With
// --yaml it ends with the configuration of every exchange seen that the configuration lacks.
// It captures passively (detail/sniff_capture.hpp): it runs beside the gateway and takes nothing.

#include <fmt/format.h>
#include <time.h>

#include <algorithm>
#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <chrono>
#include <csignal>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/cli/detail/network_load_report.hpp"
#include "app/cli/detail/run_until_stopped.hpp"
#include "app/cli/detail/sniff_capture.hpp"
#include "app/cli/detail/sniffer.hpp"
#include "eip2mqtt/adapters/clock/system_clock.hpp"
#include "eip2mqtt/adapters/udp/endpoint.hpp"
#include "eip2mqtt/adapters/udp/interfaces.hpp"
#include "eip2mqtt/adapters/udp/multicast.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/adapters/yaml/skeleton.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/core/exchange/arrival_stats.hpp"
#include "eip2mqtt/core/exchange/wire_survey.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/network_load.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/decode.hpp"
#include "eip2mqtt/core/wire/drop_reason.hpp"

namespace eip2mqtt::app {
namespace detail {

using core::wire::ExchangeKey;

Sequence apply_sequence(SniffedExchange& exchange, std::uint16_t rid, core::MonoTime now) {
    if (exchange.synchronised && exchange.plan != nullptr && exchange.plan->timeout.count() > 0 &&
        exchange.arrivals.last_arrival() &&
        now - *exchange.arrivals.last_arrival() > exchange.plan->timeout) {
        exchange.synchronised = false;
    }
    if (!exchange.synchronised) {
        exchange.synchronised = true;
        exchange.last_rid = rid;
        return Sequence::sample;
    }
    const auto d = static_cast<std::uint16_t>(rid - exchange.last_rid);
    if (d == 0) {
        ++exchange.duplicates;
        return Sequence::duplicate;
    }
    if (d >= 32768) {
        ++exchange.out_of_order;
        return Sequence::out_of_order;
    }
    exchange.missed += d - 1U;
    exchange.last_rid = rid;
    return Sequence::sample;
}

std::string local_time(core::WallTime now) {
    const auto since_epoch = now.time_since_epoch();
    const auto seconds = std::chrono::duration_cast<std::chrono::seconds>(since_epoch);
    const auto micros =
        std::chrono::duration_cast<std::chrono::microseconds>(since_epoch - seconds).count();
    const time_t t = static_cast<time_t>(seconds.count());
    struct tm parts {};
    localtime_r(&t, &parts);
    return fmt::format("{:02}:{:02}:{:02}.{:06}", parts.tm_hour, parts.tm_min, parts.tm_sec,
                       micros);
}

std::string producer_time(const core::wire::Header& header) {
    if (!header.has_timestamp()) return "none";
    const time_t t = static_cast<time_t>(header.time_s);
    struct tm parts {};
    gmtime_r(&t, &parts);
    return fmt::format("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:09}Z", parts.tm_year + 1900,
                       parts.tm_mon + 1, parts.tm_mday, parts.tm_hour, parts.tm_min, parts.tm_sec,
                       header.time_ns);
}

namespace {

std::string milliseconds(std::optional<double> seconds) {
    return seconds ? fmt::format("{:.3f}", *seconds * 1000.0) : "-";
}

}  // namespace

Sniffer::Sniffer(std::ostream& out, std::vector<core::plan::ExchangePlan> plans,
                 std::chrono::nanoseconds interval, std::optional<YamlSettings> yaml,
                 const core::Clock& clock)
    : out_(out),
      clock_(clock),
      plans_(std::move(plans)),
      configured_(core::plan::configured_rate(plans_)),
      window_start_(clock.monotonic()),
      interval_(interval),
      yaml_(std::move(yaml)) {}

void Sniffer::on_datagram(std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
                          std::uint32_t destination) {
    const auto now = clock_.monotonic();
    const auto wall = clock_.wall();
    ++wire_.datagrams;
    wire_.bytes += core::plan::wire_bytes_of_datagram(bytes.size());
    std::string line = fmt::format("{} {}", local_time(wall), adapters::udp::to_string(from));
    auto decoded = core::wire::decode_datagram(bytes);
    if (!decoded) {
        ++dropped_[decoded.error()];
        line += fmt::format(" dropped={} length={}", core::wire::to_string(decoded.error()),
                            bytes.size());
        out_ << line << std::endl;
        return;
    }
    const auto& datagram = decoded.value();
    const auto& header = datagram.header;
    auto& exchange = find_or_add(header.key());
    ++exchange.received;
    const auto sequence = apply_sequence(exchange, header.request_id, now);
    if (sequence == Sequence::sample) exchange.arrivals.on_arrival(now);
    if (exchange.survey) {
        const auto receive_ms =
            std::chrono::duration_cast<std::chrono::milliseconds>(wall.time_since_epoch()).count();
        exchange.survey->on_datagram(
            header, datagram.data.size(),
            core::exchange::classify_destination(destination, yaml_->broadcast_addresses), now,
            receive_ms);
    }

    const auto signature = core::wire::Signature::from_wire(header.signature);
    line += fmt::format(" rid={} producer={} exchange={} time={} status={} signature={} length={}",
                        header.request_id, core::wire::to_string(header.producer_id),
                        header.exchange_id, producer_time(header), header.status,
                        core::wire::to_string(signature), datagram.data.size());
    if (sequence == Sequence::duplicate) line += " duplicate";
    if (sequence == Sequence::out_of_order) line += " out_of_order";
    if (exchange.plan != nullptr) {
        line += " [" + exchange.label + "]";
        for (const auto& tag : exchange.plan->tags) {
            const auto& spec = tag.spec;
            // A datagram shorter than configured (length mismatch) lacks some tags.
            if (spec.address.byte + core::plan::tag_size(spec) > datagram.data.size()) {
                line += fmt::format(" {}=?", spec.name);
                continue;
            }
            const auto value = core::plan::decode_tag(datagram.data, spec);
            line += fmt::format(" {}={}", spec.name, core::plan::to_json(value));
        }
    }
    out_ << line << std::endl;
}

void Sniffer::print_statistics(std::uint64_t fragments, std::uint64_t kernel_drops) {
    const auto now = clock_.monotonic();
    if (exchanges_.empty() && dropped_.empty() && fragments == 0 && kernel_drops == 0) return;
    std::size_t width = 8;
    for (const auto& exchange : exchanges_) width = std::max(width, exchange.label.size());
    out_ << fmt::format("-- statistics at {} --\n", local_time(clock_.wall()));
    if (!exchanges_.empty()) {
        out_ << fmt::format("{:<{}} {:>9} {:>9} {:>10} {:>10} {:>8} {:>10} {:>12}\n", "exchange",
                            width, "received", "rate/s", "period_ms", "jitter_ms", "missed",
                            "duplicates", "out_of_order");
    }
    for (const auto& exchange : exchanges_) {
        const auto& arrivals = exchange.arrivals;
        const auto mean = arrivals.mean_period();
        out_ << fmt::format(
            "{:<{}} {:>9} {:>9.1f} {:>10} {:>10} {:>8} {:>10} {:>12}\n", exchange.label, width,
            exchange.received, arrivals.rate(now),
            milliseconds(mean ? std::optional(mean->count()) : std::nullopt),
            milliseconds(arrivals.count() > 1 ? std::optional(arrivals.jitter().count())
                                              : std::nullopt),
            exchange.missed, exchange.duplicates, exchange.out_of_order);
    }
    if (!dropped_.empty()) {
        std::string line = "dropped:";
        for (const auto& [reason, count] : dropped_) {
            line += fmt::format(" {}={}", core::wire::to_string(reason), count);
        }
        out_ << line << '\n';
    }
    if (fragments != 0) {
        out_ << fmt::format("ip fragments: {} (not decoded: EIP datagrams fit one frame)\n",
                            fragments);
    }
    if (kernel_drops != 0) {
        // The capture's own loss, not the network's: the gateway may well have them all.
        out_ << fmt::format("capture dropped: {} (sniff could not keep up)\n", kernel_drops);
    }
    print_load(now);
    out_ << std::flush;
}

void Sniffer::print_skeleton() {
    if (!yaml_) return;
    std::vector<core::exchange::WireSummary> summaries;
    for (const auto& exchange : exchanges_) {
        if (exchange.survey) summaries.push_back(exchange.survey->summary());
    }
    out_ << '\n' << adapters::yaml::yaml_skeleton(summaries) << std::flush;
}

void Sniffer::print_load(core::MonoTime now) {
    if (plans_.empty()) return;
    const std::chrono::duration<double> window = now - window_start_;
    std::string measured = "-";
    if (window.count() > 0) {
        const auto datagrams = static_cast<double>(wire_.datagrams - window_.datagrams);
        const auto bits = static_cast<double>(wire_.bytes - window_.bytes) * 8;
        measured = detail::rate(datagrams / window.count(), bits / window.count());
    }
    out_ << fmt::format(
        "load: measured {} ({} datagrams, {} bytes on the wire since start); configured {} "
        "(every configured exchange at its period)\n",
        measured, wire_.datagrams, wire_.bytes,
        detail::rate(configured_.datagrams_per_s, configured_.bits_per_s));
    window_ = wire_;
    window_start_ = now;
}

SniffedExchange& Sniffer::find_or_add(const ExchangeKey& key) {
    const auto found = index_.find(key);
    if (found != index_.end()) return exchanges_[found->second];
    const core::plan::ExchangePlan* plan = nullptr;
    for (const auto& candidate : plans_) {
        if (candidate.key() == key) {
            plan = &candidate;
            break;
        }
    }
    std::optional<std::chrono::nanoseconds> expected;
    if (plan != nullptr) expected = plan->spec.period;
    exchanges_.push_back(SniffedExchange{
        .label = plan != nullptr ? plan->spec.name
                                 : fmt::format("{}/{}", core::wire::to_string(key.producer_id),
                                               key.exchange_id),
        .plan = plan,
        .arrivals = core::exchange::ArrivalStats(expected, interval_),
    });
    if (yaml_ && plan == nullptr) exchanges_.back().survey.emplace(key, yaml_->clock_tolerance);
    index_.emplace(key, exchanges_.size() - 1);
    return exchanges_.back();
}

std::optional<SniffSetup> load_setup(const SniffOptions& options, std::ostream& err) {
    SniffSetup setup;
    if (options.yaml) {
        setup.yaml.emplace();
        setup.yaml->broadcast_addresses = adapters::udp::local_broadcast_addresses();
    }
    if (!options.config_path.empty()) {
        auto loaded = adapters::yaml::load_config(options.config_path);
        if (!loaded) {
            for (const auto& diagnostic : loaded.error()) {
                err << diagnostic.to_string() << '\n';
            }
            return std::nullopt;
        }
        const auto& config = loaded.value();
        setup.plans = core::config::make_plans(config);
        if (setup.yaml) {
            setup.yaml->clock_tolerance = config.gateway.exchange_defaults.clock_tolerance;
        }
        setup.port = config.eip.port;
        for (const auto& group : config.eip.multicast) {
            setup.groups.push_back({group.group, group.interface});
        }
    }
    if (options.port != 0) setup.port = static_cast<std::uint16_t>(options.port);
    return setup;
}

}  // namespace detail

int run_sniff(const SniffOptions& options, std::ostream& out) {
    if (!(options.interval_s > 0)) {
        std::cerr << "eip2mqtt sniff: --interval must be positive\n";
        return 2;
    }
    auto setup = detail::load_setup(options, std::cerr);
    if (!setup) return 1;
    const auto port = setup->port;

    boost::asio::io_context loop;
    auto capture = detail::open_capture(loop.get_executor(), options, port, std::cerr);
    if (!capture) return 1;
    // The groups' datagrams reach this host only while someone has joined them.
    const adapters::udp::GroupMemberships memberships(setup->groups);

    const auto interval = std::chrono::duration_cast<std::chrono::nanoseconds>(
        std::chrono::duration<double>(options.interval_s));
    const auto& clock = adapters::clock::system_clock();
    detail::Sniffer sniffer(out, std::move(setup->plans), interval, std::move(setup->yaml), clock);
    std::uint64_t seen = 0;
    capture->start([&](const adapters::capture::UdpFrame& frame) {
        if (options.count != 0 && seen >= options.count) return;
        sniffer.on_datagram(frame.payload, {frame.source, frame.source_port}, frame.destination);
        if (++seen == options.count) loop.stop();
    });
    out << fmt::format("sniffing {}:{} on {} (passive capture: the port stays the gateway's)",
                       options.bind.empty() ? "0.0.0.0" : options.bind, port, options.interface)
        << std::endl;

    boost::asio::steady_timer tick(loop);
    auto deadline = clock.monotonic() + interval;
    std::function<void()> schedule = [&] {
        tick.expires_at(deadline);
        tick.async_wait([&](const boost::system::error_code& error) {
            if (error) return;
            sniffer.print_statistics(capture->stats().fragments, capture->kernel_drops());
            deadline += interval;  // absolute deadlines: the interval never drifts
            schedule();
        });
    };
    schedule();

    detail::run_until_stopped(loop, options.duration_s);
    capture->stop();
    sniffer.print_statistics(capture->stats().fragments, capture->kernel_drops());
    sniffer.print_skeleton();
    return 0;
}

}  // namespace eip2mqtt::app
