// The exchanges of the configuration: their keys, their tags, and the point lists that add tags.

#include <cmath>

#include "adapters/yaml/detail/loader.hpp"
#include "adapters/yaml/detail/read_file.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml::detail {

void Loader::read_exchanges(const Node& node, const Mark& at, Config& config) {
    if (node.is_null()) return;
    if (!node.is_sequence()) {
        error(at, "expected a list for 'exchanges'");
        return;
    }
    int index = 0;
    for (std::size_t i = 0; i < node.size(); ++i) {
        const Node item = node.item(i);
        ++index;
        read_exchange(item, index, config);
    }
}

void Loader::read_exchange(const Node& node, int index, Config& config) {
    ExchangeConfig exchange;
    auto& spec = exchange.spec;
    ExchangeDraft draft{spec, "exchange #" + std::to_string(index)};
    if (const Node name = node.find("name"); name.is_scalar()) {
        draft.label = "exchange " + in_quotes(name.scalar());
    }
    const auto& label = draft.label;
    const std::string where = "in " + label;

    exchange.marks = walk(node, mark(node), label, where, exchange_keys,
                          [&](const std::string& key, const Node& value, const Mark& k) {
                              read_exchange_key(draft, key, value, k);
                          });
    if (!node.is_map()) return;
    for (const std::string_view required : {"name", "producer_id", "exchange_id"}) {
        if (!exchange.marks.contains(required)) {
            error(exchange.marks.node, label + " lacks " + in_quotes(required));
            draft.broken = true;
        }
    }
    if (!draft.topic_written) spec.topic = spec.name;
    spec.points = draft.points;

    if (draft.tags_node && !draft.tags_node->is_null()) {
        if (!draft.tags_node->is_sequence()) {
            error(exchange.marks.of("tags"), "expected a list for 'tags'");
        } else {
            // Sized once: vectors doubling per tag left freed blocks of every size among
            // the tags, where the long-lived plans then landed (1,000 x 100 tags: RSS
            // 29.5 MB idle, 25.2 MB sized once).
            exchange.tags.reserve(draft.tags_node->size());
            for (std::size_t i = 0; i < draft.tags_node->size(); ++i) {
                const Node item = draft.tags_node->item(i);
                if (auto tag = read_tag(item, label)) exchange.tags.push_back(std::move(*tag));
            }
        }
    }
    if (!draft.points.empty()) read_points(draft.points, exchange);
    if (!draft.broken) config.exchanges.push_back(std::move(exchange));
}

void Loader::read_exchange_key(ExchangeDraft& draft, const std::string& key, const Node& value,
                               const Mark& k) {
    auto& spec = draft.spec;
    if (key == "name") {
        if (const auto s = text(value, key, k)) {
            spec.name = *s;
        } else {
            draft.broken = true;
        }
    } else if (key == "direction") {
        const auto s = text(value, key, k);
        if (s && *s == "consume") {
            spec.direction = Direction::consume;
        } else if (s && *s == "produce") {
            spec.direction = Direction::produce;
        } else {
            if (s) error(k, "direction " + in_quotes(*s) + " is not consume or produce");
            draft.broken = true;
        }
    } else if (key == "producer_id") {
        if (const auto id = parsed(value, key, k, core::wire::parse_producer_id,
                                   "is not a.b.c.d or a plain integer (GE decimal form)")) {
            spec.producer_id = *id;
        } else {
            draft.broken = true;
        }
    } else if (key == "exchange_id") {
        if (const auto n = integer<std::uint32_t>(value, key, k)) {
            spec.exchange_id = *n;
        } else {
            draft.broken = true;
        }
    } else if (key == "length") {
        if (const auto n = integer<long long>(value, key, k)) {
            if (*n < 0 || *n > std::numeric_limits<std::uint16_t>::max()) {
                error(k, draft.label + " length " + std::to_string(*n) + " is outside 1..1400");
            } else {
                spec.length = static_cast<std::uint16_t>(*n);
            }
        }
    } else if (key == "signature") {
        if (const auto sig = parsed(value, key, k, core::wire::parse_signature,
                                    "is not major.minor (each 0..255)")) {
            spec.signature = *sig;
        }
    } else if (key == "period_ms") {
        if (const auto n = integer<long long>(value, key, k)) {
            spec.period = std::chrono::milliseconds(*n);
        }
    } else if (key == "timeout_ms") {
        if (const auto n = integer<long long>(value, key, k, 0)) {
            spec.timeout = std::chrono::milliseconds(*n);
        }
    } else if (key == "timestamp") {
        spec.timestamp = timestamp_source(value, key, k);
    } else if (key == "clock_tolerance_ms") {
        if (const auto n = integer<long long>(value, key, k, 0)) {
            spec.clock_tolerance = std::chrono::milliseconds(*n);
        }
    } else if (key == "source") {
        if (const auto ip = parsed(value, key, k, parse_ipv4, "is not an IPv4 address")) {
            spec.source = *ip;
        }
    } else if (key == "destination") {
        const auto s = text(value, key, k);
        if (s && !s->empty() && !valid_host_port(*s, false)) {
            error(k, "destination " + in_quotes(*s) + " is not host or host:port (port 1..65535)");
        } else if (s) {
            spec.destination = *s;
        }
    } else if (key == "topic") {
        if (const auto s = text(value, key, k)) spec.topic = *s;
        draft.topic_written = true;
    } else if (key == "points") {
        if (const auto s = text(value, key, k)) draft.points = *s;
    } else if (key == "tags") {
        draft.tags_node.emplace(value);
    }
}

std::optional<TagConfig> Loader::read_tag(const Node& node, const std::string& exchange_label) {
    TagConfig tag;
    auto& spec = tag.spec;
    TagDraft draft{spec};
    const auto label = [&] {
        const Node name = node.find("name");
        return (name.is_scalar() ? "tag " + in_quotes(name.scalar()) : std::string("a tag")) +
               " of " + exchange_label;
    };
    tag.marks = walk(
        node, mark(node), "tag", [&] { return "in " + label(); }, tag_keys,
        [&](const std::string& key, const Node& value, const Mark& k) {
            read_tag_key(draft, key, value, k);
        });
    if (!node.is_map()) return std::nullopt;
    for (const std::string_view required : {"name", "address", "type"}) {
        if (!tag.marks.contains(required)) {
            error(tag.marks.node, label() + " lacks " + in_quotes(required));
            draft.broken = true;
        }
    }
    if (draft.initial && !draft.broken) {
        if (auto value = read_initial(*draft.initial, spec.type, draft.initial_mark)) {
            spec.mutable_extras().initial = *value;
        } else {
            draft.broken = true;
        }
    }
    if (draft.broken) return std::nullopt;
    return tag;
}

void Loader::read_tag_key(TagDraft& draft, const std::string& key, const Node& value,
                          const Mark& k) {
    auto& spec = draft.spec;
    if (key == "name" || key == "unit" || key == "description") {
        const auto s = text(value, key, k);
        if (!s) {
            draft.broken = true;
        } else if (key == "name") {
            spec.name = *s;
        } else if (key == "unit") {
            spec.mutable_extras().unit = *s;
        } else if (!s->empty()) {
            spec.mutable_extras().description = *s;
        }
    } else if (key == "address") {
        // `126.0` unquoted is a YAML float: its scalar text is what was written.
        if (const auto address = parsed(value, key, k, core::plan::parse_address,
                                        "is not byte.bit (byte 0..65535, bit 0..7)")) {
            spec.address = *address;
        } else {
            draft.broken = true;
        }
    } else if (key == "type") {
        const auto s = text(value, key, k);
        const auto type =
            s ? core::plan::parse_tag_type(*s, core::plan::TypeNaming::yaml) : std::nullopt;
        if (type) {
            spec.type = *type;
        } else {
            if (s) {
                error(k, "unknown type " + in_quotes(*s) +
                             " (expected bit, byte, int, word, dint, udint, real, "
                             "lint or lreal)");
            }
            draft.broken = true;
        }
    } else if (key == "deadband") {
        if (const auto d = number(value, key, k)) {
            spec.deadband = *d;
        } else {
            draft.broken = true;
        }
    } else if (key == "refresh_s") {
        if (const auto n = integer<long long>(value, key, k, 0)) {
            spec.refresh = std::chrono::seconds(*n);
        } else {
            draft.broken = true;
        }
    } else if (key == "max_writes_per_s") {
        if (const auto d = number(value, key, k); d && *d >= 0) {
            spec.mutable_extras().max_writes_per_s = *d;
        } else {
            if (d) error(k, "'max_writes_per_s' must be 0 (no limit) or more");
            draft.broken = true;
        }
    } else if (key == "writable") {
        if (const auto b = boolean(value, key, k)) {
            spec.writable = *b;
        } else {
            draft.broken = true;
        }
    } else if (key == "min" || key == "max") {
        const auto d = number(value, key, k);
        if (!d) {
            draft.broken = true;
        } else if (key == "min") {
            spec.mutable_extras().min = *d;
        } else {
            spec.mutable_extras().max = *d;
        }
    } else if (key == "initial") {
        draft.initial.emplace(value);
        draft.initial_mark = k;
    }
}

std::optional<core::plan::Value> Loader::read_initial(const Node& value, TagType type,
                                                      const Mark& at) {
    const std::string_view text = value.scalar();
    switch (type) {
        case TagType::bit: {
            if (text == "0") return core::plan::Value{false};
            if (text == "1") return core::plan::Value{true};
            if (const auto b = boolean(value, "initial", at)) return core::plan::Value{*b};
            return std::nullopt;
        }
        case TagType::real:
        case TagType::lreal: {
            const auto d = number(value, "initial", at);
            if (!d) return std::nullopt;
            if (type == TagType::real && std::fabs(*d) <= std::numeric_limits<float>::max()) {
                return core::plan::Value{static_cast<float>(*d)};
            }
            return core::plan::Value{*d};
        }
        default: {
            if (const auto n = parse_integer<std::int64_t>(text)) {
                if (core::plan::type_min(type) >= 0 && *n >= 0) {
                    return core::plan::Value{static_cast<std::uint64_t>(*n)};
                }
                return core::plan::Value{*n};
            }
            if (const auto n = parse_integer<std::uint64_t>(text)) {
                return core::plan::Value{*n};
            }
            error(at, "expected an integer for 'initial'");
            return std::nullopt;
        }
    }
}

void Loader::read_points(const std::string& points, ExchangeConfig& exchange) {
    const Mark& at = exchange.marks.of("points");
    const std::filesystem::path path = dir_ / points;
    const std::string key = path.lexically_normal().string();
    auto it = point_lists_.find(key);
    if (it == point_lists_.end()) {
        auto text = read_file(path.string(), "point list " + in_quotes(path.string()));
        if (!text) {
            error(at, text.error());
            point_lists_.emplace(key, nullptr);
            return;
        }
        auto loaded = std::make_unique<LoadedPoints>(
            core::config::parse_point_list(text.value(), path.string()));
        // Errors of a file shared by several exchanges are reported once.
        diagnostics_.insert(diagnostics_.end(), loaded->list.errors.begin(),
                            loaded->list.errors.end());
        it = point_lists_.emplace(key, std::move(loaded)).first;
    }
    if (!it->second) return;
    const auto& [list, index] = *it->second;
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
        error(at, "point list " + in_quotes(points) + " has no rows whose Node is " +
                      in_quotes(exchange.spec.name));
    }
}

}  // namespace eip2mqtt::adapters::yaml::detail
