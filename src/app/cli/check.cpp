// `eip2mqtt check -c FILE`: every configuration error, or each exchange's byte map and topics.

#include <fmt/format.h>

#include <algorithm>
#include <cstddef>
#include <fstream>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <tuple>
#include <vector>

#include "app/cli/detail/network_load_report.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/northbound/mqtt_settings.hpp"
#include "eip2mqtt/app/northbound/sparkplug/sparkplug_birth_size.hpp"
#include "eip2mqtt/app/redundancy/section_summary.hpp"
#include "eip2mqtt/core/config/config.hpp"
#include "eip2mqtt/core/config/placeholders.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/plan/overlap.hpp"
#include "eip2mqtt/core/plan/plan_warnings.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::app {
namespace {

using core::plan::Direction;
using core::plan::ExchangePlan;
using core::plan::TagPlan;
using core::plan::TagType;

/// A scaled tag's scale on its byte-map line: `scale 0..32000 -> 0..100 %, clamped`,
/// `scale sqrt 0..65535 -> 0..500 m3/h`, `scale x 0.1 + -40 degC`.
std::string scale_text(const core::plan::TagSpec& tag) {
    const auto& s = *tag.scale();
    const std::string unit = tag.unit().empty() ? "" : " " + tag.unit();
    if (s.kind == core::plan::ScaleKind::gain_offset) {
        return fmt::format("scale x {} + {}{}", s.gain, s.offset, unit);
    }
    return fmt::format("scale {}{}..{} -> {}..{}{}{}",
                       s.kind == core::plan::ScaleKind::square_root ? "sqrt " : "", s.raw.lo,
                       s.raw.hi, s.eu.lo, s.eu.hi, unit, s.clamp ? ", clamped" : "");
}

std::string size_text(const core::plan::TagSpec& tag) {
    if (tag.type == TagType::bit) {
        return tag.count == 1 ? "1 bit" : std::to_string(tag.count) + " bits";
    }
    const auto size = core::plan::tag_size(tag);
    auto text = std::to_string(size) + (size == 1 ? " byte" : " bytes");
    if (tag.is_array()) text += " (" + std::to_string(tag.count) + " elements)";
    return text;
}

/// "bytes 0-118, 121-125 unused", or "no unused bytes".
std::string unused_ranges(const ExchangePlan& plan) {
    std::vector<bool> used(plan.length, false);
    for (const auto& tag : plan.tags) {
        const std::size_t first = tag.spec.address.byte;
        const std::size_t end =
            std::min<std::size_t>(first + core::plan::tag_size(tag.spec), plan.length);
        for (std::size_t b = first; b < end; ++b) used[b] = true;
    }
    std::string ranges;
    std::size_t count = 0;
    for (std::size_t b = 0; b < used.size();) {
        if (used[b]) {
            ++b;
            continue;
        }
        std::size_t e = b;
        while (e + 1 < used.size() && !used[e + 1]) ++e;
        if (!ranges.empty()) ranges += ", ";
        ranges += e == b ? std::to_string(b) : std::to_string(b) + "-" + std::to_string(e);
        count += e - b + 1;
        b = e + 1;
    }
    if (count == 0) return "no unused bytes";
    return (count == 1 ? "byte " : "bytes ") + ranges + " unused";
}

std::string described(const TagPlan& tag) {
    return tag.spec.name + " (" + core::plan::to_string(tag.spec.address) + ", " +
           std::string(core::plan::to_string(tag.spec.type)) + ")";
}

/// Overlaps are valid (a word and its bits, a dint and its halves): noted, so that one made by
/// mistake is seen. A point list can alias one word thousands of times: the list is bounded.
void print_overlaps(const ExchangePlan& plan, std::ostream& out) {
    constexpr std::size_t max_listed = 1000;
    std::vector<core::plan::BitSpan> spans;
    spans.reserve(plan.tags.size());
    for (const auto& tag : plan.tags) spans.push_back(core::plan::bit_span(tag.spec));
    const auto overlaps = core::plan::find_overlaps(spans, max_listed);
    for (const auto& [first, second] : overlaps.listed) {
        out << "  note: " << described(plan.tags[second]) << " overlaps "
            << described(plan.tags[first]) << "\n";
    }
    if (overlaps.total > overlaps.listed.size()) {
        out << "  note: and " << overlaps.total - overlaps.listed.size() << " more overlaps\n";
    }
}

void print_exchange(const ExchangePlan& plan, std::ostream& out) {
    const auto& spec = plan.spec;
    const bool produce = spec.direction == Direction::produce;
    out << "exchange " << spec.name << ": " << (produce ? "produce" : "consume") << ", producer "
        << core::wire::to_string(spec.producer_id) << ", exchange " << spec.exchange_id << ", "
        << plan.length << " bytes, period " << spec.period.count() << " ms";
    if (!produce) {
        out << ", timeout ";
        if (plan.timeout.count() == 0) {
            out << "off";
        } else {
            out << plan.timeout.count() << " ms";
        }
    }
    out << ", signature "
        << (spec.signature.is_set() ? core::wire::to_string(spec.signature) : "none");
    if (produce) out << ", destination " << spec.destination;
    out << "\n  topic " << plan.topic << " (" << plan.status_topic;
    if (produce) out << ", writes " << plan.set_topic;
    out << ")\n";

    std::vector<const TagPlan*> tags;
    for (const auto& tag : plan.tags) tags.push_back(&tag);
    std::stable_sort(tags.begin(), tags.end(), [](const TagPlan* a, const TagPlan* b) {
        return std::tuple(a->spec.address.byte, a->spec.address.bit) <
               std::tuple(b->spec.address.byte, b->spec.address.bit);
    });
    for (const auto* tag : tags) {
        const auto address = core::plan::to_string(tag->spec.address);
        out << "  " << address << std::string(address.size() < 7 ? 7 - address.size() : 1, ' ')
            << std::left << std::setw(7) << core::plan::to_string(tag->spec.type);
        // An array's size is wider than the column: a space still parts it from the topic.
        const auto size = size_text(tag->spec);
        out << std::setw(9) << size << (size.size() < 9 ? "" : " ") << plan.tag_topic(*tag);
        if (tag->spec.writable) out << "  writable";
        if (tag->spec.scale()) out << "  " << scale_text(tag->spec);
        out << std::right << "\n";
    }
    print_overlaps(plan, out);
    // Valid: traffic can be watched before the byte map is known.
    if (plan.tags.empty()) out << "  no tags yet: only " << plan.status_topic << " is published\n";
    out << "  " << unused_ranges(plan) << "\n";
}

/// A Sparkplug birth's largest size, and a warning when it is over `max_packet_bytes` (when
/// set) or the 128 KiB some brokers take: a birth over the broker's limit is never published.
void print_birth_size(std::string_view birth, std::size_t bytes, std::size_t max_packet_bytes,
                      std::ostream& out) {
    out << "  sparkplug " << birth << ": at most " << bytes << " bytes\n";
    const bool set = max_packet_bytes != 0;
    const auto limit = set ? max_packet_bytes : northbound::sparkplug::common_max_packet_bytes;
    if (bytes <= limit) return;
    const auto whom = birth == "NBIRTH" ? "the edge node" : "this device";
    out << "  warning: the Sparkplug " << birth << " may take " << bytes << " bytes, over ";
    if (set) {
        out << "sparkplug.max_packet_bytes (" << limit << "): it would not be published, and "
            << whom << " never born";
    } else {
        out << "the " << limit << " bytes some brokers take: one whose Maximum Packet Size is "
            << "lower refuses it, and " << whom << " is never born (set "
            << "sparkplug.max_packet_bytes to your broker's limit)";
    }
    out << "; split the exchange, shorten its names, or use a broker that takes larger "
           "packets\n";
}

/// One warning per placeholder `import-points` left (core/config/placeholders.hpp). The file
/// was just read whole by the loader; reading it again keeps the loader unaware of comments.
void print_placeholders(const std::string& config_path, std::ostream& out) {
    std::ifstream file(config_path, std::ios::binary);
    std::ostringstream text;
    text << file.rdbuf();
    for (const auto& placeholder : core::config::find_placeholders(text.str(), config_path)) {
        const auto& at = placeholder.mark;
        out << at.file.str() << ":" << at.line << ":" << at.column
            << ": warning: " << (placeholder.key.empty() ? "a value" : placeholder.key)
            << " is still a placeholder: set it, then remove the "
            << core::config::placeholder_marker << " comment\n";
    }
}

/// What eip.commands leaves unanswered that a reader might not expect.
void print_commands(const core::config::CommandsSection& commands, std::ostream& out) {
    if (!commands.allow || !commands.allow->empty()) return;
    const auto& at = commands.marks.of("allow");
    out << at.file.str() << ":" << at.line << ":" << at.column
        << ": warning: eip.commands.allow is empty: the command port answers nobody (leave "
           "'allow' out for the subnets of eip.bind)\n";
}

/// MQTT 5 metadata that MQTT 3.1.1 cannot carry: said, not refused (a configuration may name
/// the broker's version before the broker is upgraded).
void print_mqtt5_only(const core::config::MqttSection& mqtt, std::ostream& out) {
    if (mqtt.version == 5) return;
    for (const auto* key :
         {"describe_payloads", "properties", "message_expiry_s", "topic_aliases"}) {
        if (!mqtt.marks.contains(key)) continue;
        const auto& at = mqtt.marks.of(key);
        out << at.file.str() << ":" << at.line << ":" << at.column << ": warning: mqtt." << key
            << " is ignored with MQTT 3.1.1, which has no properties\n";
    }
}

}  // namespace

int run_check(const std::string& config_path, std::ostream& out, std::ostream& err) {
    const auto config = adapters::yaml::load_config(config_path);
    if (!config) {
        for (const auto& diagnostic : config.error()) err << diagnostic.to_string() << "\n";
        err << config.error().size() << " error(s)\n";
        return 1;
    }
    const auto plans = core::config::make_plans(*config);
    out << config_path << ": valid, " << plans.size()
        << (plans.size() == 1 ? " exchange" : " exchanges") << ", base topic "
        << config->mqtt.base_topic << "\n";
    out << connections_summary(*config);
    out << redundancy::section_summary(config->redundancy);
    print_placeholders(config_path, out);
    print_commands(config->eip.commands, out);
    print_mqtt5_only(config->mqtt, out);
    const core::plan::WarningContext context{config->mqtt.version == 3};
    const auto& sparkplug = config->sparkplug;
    std::optional<northbound::sparkplug::SparkplugBirthSizes> births;
    if (sparkplug.enabled()) {
        births = northbound::sparkplug::sparkplug_birth_sizes(
            northbound::sparkplug::sparkplug_options(*config), plans);
        print_birth_size("NBIRTH", births->node, sparkplug.max_packet_bytes, out);
    }
    for (std::size_t i = 0; i < plans.size(); ++i) {
        out << "\n";
        print_exchange(plans[i], out);
        for (const auto& warning : core::plan::plan_warnings(plans[i], context)) {
            out << "  warning: " << warning << "\n";
        }
        if (births) print_birth_size("DBIRTH", births->devices[i], sparkplug.max_packet_bytes, out);
    }
    return detail::report_network_load(plans, config->eip.link_mbps, out, err) ? 0 : 1;
}

}  // namespace eip2mqtt::app
