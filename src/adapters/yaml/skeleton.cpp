#include "eip2mqtt/adapters/yaml/skeleton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string_view>

#include "adapters/yaml/detail/skeleton_lines.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml {
namespace {

namespace exchange = core::exchange;
namespace wire = core::wire;

using exchange::ClockState;
using exchange::DestinationKind;
using exchange::WireSummary;

constexpr long default_period_ms = 1000;

std::string three_decimals(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.3f", value);
    return text;
}

std::string plural(std::uint64_t count, std::string_view one, std::string_view many) {
    return std::to_string(count) + " " + std::string(count == 1 ? one : many);
}

void length_line(const WireSummary& s, std::string& out) {
    if (s.length == 0) {
        out += "    length: 1  # TODO: the datagrams carry no data; a length is 1 to 1400 bytes\n";
        return;
    }
    out += "    length: " + std::to_string(s.length) + "  # data bytes";
    if (s.min_length != s.max_length) {
        out += " of the last datagram; lengths " + std::to_string(s.min_length) + " to " +
               std::to_string(s.max_length) + " seen: check which is right";
    }
    out += "\n";
}

void signature_line(const WireSummary& s, std::string& out) {
    const std::string_view varied = s.signature_varied ? "; it varied: the last datagram's" : "";
    if (s.signature.is_set()) {
        out += "    signature: \"" + wire::to_string(s.signature) + "\"";
        if (s.signature_varied) out += "  # it varied: the last datagram's";
        out += "\n";
    } else {
        out += "    # signature: none (the producer sends 0.0" + std::string(varied) + ")\n";
    }
}

void period_line(const WireSummary& s, std::string& out) {
    if (!s.period_ms) {
        out += "    period_ms: " + std::to_string(default_period_ms) +
               "  # TODO: not measured (no two datagrams in sequence); the default\n";
        return;
    }
    const long rounded = std::lround(*s.period_ms);
    const long min_period = detail::min_period_ms;
    const long max_period = detail::max_period_ms;
    const long period = rounded < min_period   ? min_period
                        : rounded > max_period ? max_period
                                               : rounded;
    out += "    period_ms: " + std::to_string(period) + "  # measured " +
           three_decimals(*s.period_ms) +
           " ms: time between receive times per request-id step, over " +
           plural(s.period_steps, "step", "steps");
    if (period != rounded) {
        out += "; period_ms is " + std::to_string(min_period) + " to " + std::to_string(max_period);
    }
    out += "\n";
}

void destination_line(const WireSummary& s, std::string& out) {
    const auto& d = s.destination;
    out += "    # destination: ";
    out += d.kind == DestinationKind::unknown ? "unknown (the receiving socket did not say)"
                                              : detail::destination_text(d.kind, d.address);
    if (s.destination_varied) out += "; it varied: the last datagram's";
    out += "\n";
}

void clock_line(const WireSummary& s, std::string& out) {
    out += "    # clock: " + std::string(exchange::to_string(s.clock)) + " (";
    const auto tolerance = std::to_string(s.clock_tolerance.count());
    if (s.clock == ClockState::none || !s.clock_offset_ms) {
        out += "no timestamp in the datagrams: tags carry the receive time";
    } else {
        const auto offset = *s.clock_offset_ms;
        out += "the producer's time is " + std::to_string(offset < 0 ? -offset : offset) + " ms " +
               (offset < 0 ? "behind" : "ahead of") + " the receive time, ";
        out +=
            s.clock == ClockState::synced
                ? "within " + tolerance + " ms"
                : "beyond " + tolerance + " ms: with timestamp auto, tags carry the receive time";
    }
    out += ")";
    if (s.clock_varied) out += "; it varied: the last datagram's";
    out += "\n";
}

}  // namespace

std::string skeleton_topic(const wire::ExchangeKey& key) {
    auto producer = wire::to_string(key.producer_id);
    std::replace(producer.begin(), producer.end(), '.', '-');
    return producer + "/" + std::to_string(key.exchange_id);
}

std::string yaml_skeleton(std::span<const WireSummary> exchanges) {
    if (exchanges.empty()) {
        return "# sniff --yaml: no exchange seen on the wire that the configuration lacks\n";
    }
    std::string out = "# sniff --yaml: " + plural(exchanges.size(), "exchange", "exchanges") +
                      " seen on the wire that the configuration lacks. Rename at will; add tags "
                      "where the byte map is known.\n"
                      "exchanges:\n";
    for (const auto& s : exchanges) {
        detail::item_head(s.key, out);
        length_line(s, out);
        signature_line(s, out);
        period_line(s, out);
        out += "    topic: \"" + skeleton_topic(s.key) + "\"  # under base_topic\n";
        destination_line(s, out);
        clock_line(s, out);
        out += "    # seen: " + plural(s.datagrams, "datagram", "datagrams") + "\n";
        out += "    tags: []  # TODO: the byte map; until then only {topic}/_status is published\n";
    }
    return out;
}

}  // namespace eip2mqtt::adapters::yaml
