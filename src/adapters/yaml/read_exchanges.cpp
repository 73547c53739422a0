// The exchanges of the configuration: their keys, their tags, and the point lists that add tags.

#include <cmath>

#include "adapters/yaml/detail/key_readers.hpp"
#include "adapters/yaml/detail/read_engineering.hpp"
#include "adapters/yaml/detail/read_initial.hpp"
#include "adapters/yaml/detail/sections.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

namespace keys = core::config::keys;

/// An exchange while its keys are read.
struct ExchangeDraft {
    core::plan::ExchangeSpec& spec;
    std::string label;    ///< how messages name it
    bool broken = false;  ///< an identity key is missing or bad: leave it out of the model
    std::optional<Node> tags_node;
    std::string points;
    bool topic_written = false;
};

/// A tag while its keys are read.
struct TagDraft {
    core::plan::TagSpec& spec;
    bool broken = false;  ///< a value failed to parse: leave the tag out of the model
    std::optional<Node> initial;
    Mark initial_mark;
    EngineeringDraft engineering;
};

/// The keys whose bad value leaves their exchange out of the model (what names it on the wire).
bool is_identity_key(std::string_view key) {
    return key == "name" || key == "direction" || key == "producer_id" || key == "exchange_id";
}

bool read_length(KeyValue& v, ExchangeDraft& d) {
    const auto n = v.integer<long long>();
    if (!n) return false;
    if (*n < 0 || *n > std::numeric_limits<std::uint16_t>::max()) {
        v.error(d.label + " length " + std::to_string(*n) + " is outside 1..1400");
        return false;
    }
    d.spec.length = static_cast<std::uint16_t>(*n);
    return true;
}

bool read_destination(KeyValue& v, ExchangeDraft& d) {
    const auto s = v.text();
    if (s && !s->empty() && !valid_host_port(*s, false)) {
        v.error("destination " + in_quotes(*s) + " is not host or host:port (port 1..65535)");
        return false;
    }
    if (s) d.spec.destination = *s;
    return s.has_value();
}

/// Stores what `v.parsed(parse, problem)` reads in `field`.
template <class Field, class Parse>
bool parsed_to(KeyValue& v, Field& field, Parse parse, std::string_view problem) {
    const auto value = v.parsed(parse, problem);
    if (value) field = *value;
    return value.has_value();
}

/// An entry of `exchanges`, while it is read.
constexpr KeyReader<ExchangeDraft> exchange_rows[]{
    {"name", [](KeyValue& v, ExchangeDraft& d) { return v.text_to(d.spec.name); }},
    {"direction",
     [](KeyValue& v, ExchangeDraft& d) {
         return parsed_to(
             v, d.spec.direction,
             [](std::string_view s) { return core::plan::direction_names.parse(s); },
             "is not consume or produce");
     }},
    {"producer_id",
     [](KeyValue& v, ExchangeDraft& d) {
         return parsed_to(v, d.spec.producer_id, core::wire::parse_producer_id,
                          "is not a.b.c.d or a plain integer (GE decimal form)");
     }},
    {"exchange_id",
     [](KeyValue& v, ExchangeDraft& d) { return v.integer_to<std::uint32_t>(d.spec.exchange_id); }},
    {"length", read_length},
    {"signature",
     [](KeyValue& v, ExchangeDraft& d) {
         return parsed_to(v, d.spec.signature, core::wire::parse_signature,
                          "is not major.minor (each 0..255)");
     }},
    {"period_ms",
     [](KeyValue& v, ExchangeDraft& d) { return v.integer_to<long long>(d.spec.period); }},
    {"timeout_ms",
     [](KeyValue& v, ExchangeDraft& d) { return v.integer_to<long long>(d.spec.timeout, 0); }},
    {"timestamp",
     [](KeyValue& v, ExchangeDraft& d) {
         d.spec.timestamp = v.timestamp_source();
         return d.spec.timestamp.has_value();
     }},
    {"clock_tolerance_ms",
     [](KeyValue& v, ExchangeDraft& d) {
         return v.integer_to<long long>(d.spec.clock_tolerance, 0);
     }},
    {"source",
     [](KeyValue& v, ExchangeDraft& d) {
         return parsed_to(v, d.spec.source, parse_ipv4, "is not an IPv4 address");
     }},
    {"destination", read_destination},
    {"topic",
     [](KeyValue& v, ExchangeDraft& d) {
         d.topic_written = true;
         return v.text_to(d.spec.topic);
     }},
    {"points", [](KeyValue& v, ExchangeDraft& d) { return v.text_to(d.points); }},
    {"publish_raw", [](KeyValue& v, ExchangeDraft& d) { return v.boolean_to(d.spec.publish_raw); }},
    {"location", [](KeyValue& v, ExchangeDraft& d) { return v.location_to(d.spec.location); }},
    {"tags",
     [](KeyValue& v, ExchangeDraft& d) {
         d.tags_node.emplace(v.node());
         return true;
     }},
};
constexpr auto exchange_readers = bind_keys(keys::exchange, exchange_rows);

bool read_type(KeyValue& v, TagDraft& d) {
    const auto s = v.text();
    const auto type =
        s ? core::plan::parse_tag_type(*s, core::plan::TypeNaming::yaml) : std::nullopt;
    if (type) {
        d.spec.type = *type;
    } else if (s) {
        std::string message = "unknown type " + in_quotes(*s);
        if (const auto hint = core::plan::tag_type_hint(*s)) {
            message += " (did you mean " + in_quotes(*hint) + "?)";
        }
        v.error(message +
                "; expected bit, byte, int, word, dint, udint, real, lint, lreal or string, " +
                "or the aliases " + std::string(core::plan::tag_type_aliases));
    }
    return type.has_value();
}

/// The settings few tags have live out of line (TagSpec::extras): only a value read makes room.
template <class T, class Field>
bool extra_to(TagDraft& d, const std::optional<T>& value, Field core::plan::TagExtras::*field) {
    if (value) d.spec.mutable_extras().*field = *value;
    return value.has_value();
}

/// An entry of an exchange's `tags`, while it is read.
constexpr KeyReader<TagDraft> tag_rows[]{
    {"name", [](KeyValue& v, TagDraft& d) { return v.text_to(d.spec.name); }},
    // `126.0` unquoted is a YAML float: its scalar text is what was written.
    {"address",
     [](KeyValue& v, TagDraft& d) {
         return parsed_to(v, d.spec.address, core::plan::parse_address,
                          "is not byte.bit (byte 0..65535, bit 0..7)");
     }},
    {"type", read_type},
    {"unit",
     [](KeyValue& v, TagDraft& d) { return extra_to(d, v.text(), &core::plan::TagExtras::unit); }},
    {"deadband",
     [](KeyValue& v, TagDraft& d) { return read_deadband(v, d.spec.deadband, d.engineering); }},
    {"refresh_s",
     [](KeyValue& v, TagDraft& d) { return v.integer_to<long long>(d.spec.refresh, 0); }},
    {"writable", [](KeyValue& v, TagDraft& d) { return v.boolean_to(d.spec.writable); }},
    {"min",
     [](KeyValue& v, TagDraft& d) { return extra_to(d, v.number(), &core::plan::TagExtras::min); }},
    {"max",
     [](KeyValue& v, TagDraft& d) { return extra_to(d, v.number(), &core::plan::TagExtras::max); }},
    {"initial",
     [](KeyValue& v, TagDraft& d) {
         d.initial.emplace(v.node());
         d.initial_mark = v.at();
         return true;
     }},
    {"description",
     [](KeyValue& v, TagDraft& d) {
         const auto s = v.text();
         if (s && !s->empty()) d.spec.mutable_extras().description = *s;
         return s.has_value();
     }},
    {"max_writes_per_s",
     [](KeyValue& v, TagDraft& d) {
         const auto rate = v.number();
         if (rate && *rate < 0) {
             v.error("'max_writes_per_s' must be 0 (no limit) or more");
             return false;
         }
         return extra_to(d, rate, &core::plan::TagExtras::max_writes_per_s);
     }},
    {"scale", [](KeyValue& v, TagDraft& d) { return read_scale(v, d.engineering); }},
    {"type_eu", [](KeyValue& v, TagDraft& d) { return read_type_eu(v, d.engineering); }},
    {"publish_raw",
     [](KeyValue& v, TagDraft& d) {
         return extra_to(d, v.boolean(), &core::plan::TagExtras::publish_raw);
     }},
    // Both are the tag's count: of elements, or of a string's bytes. Their ranges by type are
    // the core's to check.
    {"count",
     [](KeyValue& v, TagDraft& d) { return v.integer_to<std::uint16_t>(d.spec.count, 1); }},
    {"length",
     [](KeyValue& v, TagDraft& d) { return v.integer_to<std::uint16_t>(d.spec.count, 0); }},
    {"trim", [](KeyValue& v,
                TagDraft& d) { return extra_to(d, v.boolean(), &core::plan::TagExtras::trim); }},
    {"location",
     [](KeyValue& v, TagDraft& d) {
         auto location = v.location();
         if (location && !location->empty())
             d.spec.mutable_extras().location = std::move(*location);
         return location.has_value();
     }},
    {"topic_name",
     [](KeyValue& v, TagDraft& d) {
         return extra_to(d, v.text(), &core::plan::TagExtras::topic_name);
     }},
    {"topic",
     [](KeyValue& v, TagDraft& d) { return extra_to(d, v.text(), &core::plan::TagExtras::topic); }},
};
constexpr auto tag_readers = bind_keys(keys::tag, tag_rows);

std::optional<TagConfig> read_tag(Reader& reader, const Node& node,
                                  const std::string& exchange_label) {
    TagConfig tag;
    auto& spec = tag.spec;
    TagDraft draft{spec};
    const auto label = [&] {
        const Node name = node.find("name");
        return (name.is_scalar() ? "tag " + in_quotes(name.scalar()) : std::string("a tag")) +
               " of " + exchange_label;
    };
    tag.marks = reader.read_keys(
        node, reader.mark(node), "tag", [&] { return "in " + label(); }, tag_readers, draft,
        [&](std::string_view) { draft.broken = true; });
    if (!node.is_map()) return std::nullopt;
    for (const std::string_view required : {"name", "address", "type"}) {
        if (!tag.marks.contains(required)) {
            reader.error(tag.marks.node, label() + " lacks " + in_quotes(required));
            draft.broken = true;
        }
    }
    if (!draft.broken && !finish_engineering(reader, draft.engineering, tag)) draft.broken = true;
    if (draft.initial && !draft.broken) {
        if (auto value = read_tag_initial(reader, *draft.initial, spec, draft.initial_mark)) {
            spec.mutable_extras().initial = std::move(*value);
        } else {
            draft.broken = true;
        }
    }
    if (draft.broken) return std::nullopt;
    return tag;
}

/// docs/protocol.md §6: the rows of the point list whose Node is this exchange.
void read_points(Reader& reader, PointLists& point_lists, const std::string& points,
                 ExchangeConfig& exchange) {
    const Mark& at = exchange.marks.of("points");
    const LoadedPoints* loaded = point_lists.find(points, at, reader);
    if (!loaded) return;
    const auto& [list, index] = *loaded;
    const auto rows = index.rows_of(exchange.spec.name);
    exchange.tags.reserve(exchange.tags.size() + rows.size());
    for (const auto row_index : rows) {
        const auto& row = list.rows[row_index];
        TagConfig tag;
        tag.spec = row.tag;
        tag.spec.writable = row.write;
        tag.marks.node = row.mark;
        exchange.tags.push_back(std::move(tag));
    }
    if (rows.empty() && list.errors.empty()) {
        reader.error(at, "point list " + in_quotes(points) + " has no rows whose Node is " +
                             in_quotes(exchange.spec.name));
    }
}

void read_exchange(Reader& reader, PointLists& point_lists, const Node& node, int index,
                   Config& config) {
    ExchangeConfig exchange;
    auto& spec = exchange.spec;
    ExchangeDraft draft{spec, "exchange #" + std::to_string(index)};
    if (const Node name = node.find("name"); name.is_scalar()) {
        draft.label = "exchange " + in_quotes(name.scalar());
    }
    const auto& label = draft.label;
    const std::string where = "in " + label;

    const auto failed = [&](std::string_view key) {
        draft.broken = draft.broken || is_identity_key(key);
    };
    exchange.marks =
        reader.read_keys(node, reader.mark(node), label, where, exchange_readers, draft, failed);
    if (!node.is_map()) return;
    for (const std::string_view required : {"name", "producer_id", "exchange_id"}) {
        if (!exchange.marks.contains(required)) {
            reader.error(exchange.marks.node, label + " lacks " + in_quotes(required));
            draft.broken = true;
        }
    }
    if (!draft.topic_written) spec.topic = spec.name;
    spec.points = draft.points;

    if (draft.tags_node && !draft.tags_node->is_null()) {
        if (!draft.tags_node->is_sequence()) {
            reader.error(exchange.marks.of("tags"), "expected a list for 'tags'");
        } else {
            // Sized once: vectors doubling per tag left freed blocks of every size among
            // the tags, where the long-lived plans then landed
            // (docs/decisions/0001-configurations-of-100000-tags.md).
            exchange.tags.reserve(draft.tags_node->size());
            for (std::size_t i = 0; i < draft.tags_node->size(); ++i) {
                const Node item = draft.tags_node->item(i);
                if (auto tag = read_tag(reader, item, label))
                    exchange.tags.push_back(std::move(*tag));
            }
        }
    }
    if (!draft.points.empty()) read_points(reader, point_lists, draft.points, exchange);
    if (spec.publish_raw) {
        for (auto& tag : exchange.tags) {
            if (!tag.marks.contains("publish_raw")) tag.spec.mutable_extras().publish_raw = true;
        }
    }
    if (!draft.broken) config.exchanges.push_back(std::move(exchange));
}

}  // namespace

void read_exchanges(Reader& reader, PointLists& point_lists, const Node& node, const Mark& at,
                    Config& config) {
    if (node.is_null()) return;
    if (!node.is_sequence()) {
        reader.error(at, "expected a list for 'exchanges'");
        return;
    }
    int index = 0;
    for (std::size_t i = 0; i < node.size(); ++i) {
        const Node item = node.item(i);
        ++index;
        read_exchange(reader, point_lists, item, index, config);
    }
}

}  // namespace eip2mqtt::adapters::yaml::detail
