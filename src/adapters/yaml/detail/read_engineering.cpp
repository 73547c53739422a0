// A tag's engineering keys: `scale`, `type_eu`, `deadband` as a mapping, `initial` in units.

#include "adapters/yaml/detail/read_engineering.hpp"

#include <cmath>

namespace eip2mqtt::adapters::yaml::detail {
namespace {

namespace keys = core::config::keys;
using core::plan::ScaleKind;
using core::plan::ScaleRange;
using core::plan::Scaling;

/// A `scale` mapping while its keys are read.
struct ScaleDraft {
    Scaling scaling;
    bool broken = false;
};

bool range_to(KeyValue& v, ScaleDraft& d, ScaleRange Scaling::*field) {
    const auto pair = v.number_pair();
    if (pair) d.scaling.*field = ScaleRange{(*pair)[0], (*pair)[1]};
    d.broken = d.broken || !pair;
    return pair.has_value();
}

template <class T, class Store>
bool stored(ScaleDraft& d, const std::optional<T>& value, Store store) {
    if (value) store(*value);
    d.broken = d.broken || !value;
    return value.has_value();
}

constexpr KeyReader<ScaleDraft> scale_rows[]{
    {"raw", [](KeyValue& v, ScaleDraft& d) { return range_to(v, d, &Scaling::raw); }},
    {"eu", [](KeyValue& v, ScaleDraft& d) { return range_to(v, d, &Scaling::eu); }},
    {"sqrt",
     [](KeyValue& v, ScaleDraft& d) {
         return stored(d, v.boolean(), [&](bool on) {
             if (on) d.scaling.kind = ScaleKind::square_root;
         });
     }},
    {"clamp",
     [](KeyValue& v, ScaleDraft& d) {
         return stored(d, v.boolean(), [&](bool on) { d.scaling.clamp = on; });
     }},
    {"gain",
     [](KeyValue& v, ScaleDraft& d) {
         return stored(d, v.number(), [&](double gain) { d.scaling.gain = gain; });
     }},
    {"offset",
     [](KeyValue& v, ScaleDraft& d) {
         return stored(d, v.number(), [&](double offset) { d.scaling.offset = offset; });
     }},
};
constexpr auto scale_readers = bind_keys(keys::scale, scale_rows);

constexpr KeyReader<std::optional<double>> deadband_rows[]{
    {"percent",
     [](KeyValue& v, std::optional<double>& percent) {
         percent = v.number();
         return percent.has_value();
     }},
};
constexpr auto deadband_readers = bind_keys(keys::deadband, deadband_rows);

void keep_marks(EngineeringDraft& d, std::string_view key, const Marks& inner) {
    for (const auto& [name, at] : inner.keys)
        d.marks.emplace_back(std::string(key) + "." + name, at);
}

/// The scale's kind follows its keys: gain and offset, or raw and eu (with sqrt, a square
/// root). False, reported, when they mix or one is missing.
bool pick_kind(KeyValue& v, const Marks& marks, Scaling& s) {
    const bool by_gain = marks.contains("gain") || marks.contains("offset");
    const bool by_ranges = marks.contains("raw") || marks.contains("eu") || marks.contains("sqrt");
    if (by_gain && by_ranges) {
        v.error(
            "'scale' takes raw and eu (with sqrt for a square root), or gain and offset, "
            "not both");
        return false;
    }
    if (by_gain) {
        if (s.clamp) {
            v.error("'clamp' needs the ranges raw and eu to clamp to; gain and offset have none");
            return false;
        }
        s.kind = ScaleKind::gain_offset;
        return true;
    }
    for (const std::string_view needed : {"raw", "eu"}) {
        if (!marks.contains(needed)) {
            v.error("'scale' lacks " + in_quotes(needed) +
                    " (raw and eu, or gain and offset, say how raw values become units)");
            return false;
        }
    }
    return true;
}

}  // namespace

bool read_scale(KeyValue& v, EngineeringDraft& d) {
    if (v.node().is_null()) return true;
    ScaleDraft draft;
    const Marks marks = v.mapping("in 'scale'", scale_readers, draft);
    // A key that was unknown or repeated is reported already: what the scale lacks then says
    // nothing more.
    const bool every_key_read = v.node().is_map() && marks.keys.size() == v.node().size();
    if (!every_key_read || draft.broken || !pick_kind(v, marks, draft.scaling)) return false;
    keep_marks(d, "scale", marks);
    d.scale = draft.scaling;
    return true;
}

bool read_type_eu(KeyValue& v, EngineeringDraft& d) {
    const auto name = v.text();
    if (!name) return false;
    const auto type = core::plan::parse_tag_type(*name, core::plan::TypeNaming::yaml);
    if (!type || *type == core::plan::TagType::bit) {
        v.error("'type_eu' " + in_quotes(*name) +
                " is no type an engineering value takes; expected byte, int, word, dint, udint, "
                "lint, real or lreal");
        return false;
    }
    d.eu_type = type;
    d.eu_type_mark = v.at();
    return true;
}

bool read_deadband(KeyValue& v, double& absolute, EngineeringDraft& d) {
    if (!v.node().is_map()) return v.number_to(absolute);
    std::optional<double> percent;
    const Marks marks = v.mapping("in 'deadband'", deadband_readers, percent);
    if (!marks.contains("percent")) {
        v.error("'deadband' as a mapping takes 'percent' (of the engineering span)");
        return false;
    }
    keep_marks(d, "deadband", marks);
    d.deadband_percent = percent;
    return percent.has_value();
}

bool finish_engineering(Reader& reader, EngineeringDraft& d, TagConfig& tag) {
    auto& spec = tag.spec;
    for (auto& [key, at] : d.marks) tag.marks.add(key, at);
    if (d.eu_type && !d.scale) {
        reader.error(d.eu_type_mark, "'type_eu' is the type of a scaled value: add 'scale'");
        return false;
    }
    if (d.scale) {
        d.scale->eu_type = d.eu_type;
        spec.mutable_extras().scale = d.scale;
    }
    if (d.deadband_percent) {
        spec.mutable_extras().deadband_percent = d.deadband_percent;
        // The span: the scale's, else min..max; without either the core refuses the tag.
        std::optional<ScaleRange> span = d.scale ? core::plan::eu_span(*d.scale) : std::nullopt;
        if (!span && spec.min() && spec.max()) span = ScaleRange{*spec.min(), *spec.max()};
        if (span) spec.deadband = *d.deadband_percent / 100.0 * (span->hi - span->lo);
    }
    return true;
}

std::optional<core::plan::Value> read_initial_eu(Reader& reader, const Node& value,
                                                 const core::plan::Scaling& scale,
                                                 core::plan::TagType wire, const Mark& at) {
    const auto eu = reader.number(value, "initial", at);
    if (!eu) return std::nullopt;
    if (!std::isfinite(*eu)) {
        reader.error(at, "'initial' must be a finite number");
        return std::nullopt;
    }
    auto raw = core::plan::to_raw(*eu, scale, wire);
    if (!raw) {
        reader.error(at, raw.error() == core::plan::RawRefusal::below_zero
                             ? "'initial' is below the square root's zero: no raw value reads so"
                             : "'initial' in raw form is outside the range of " +
                                   std::string(core::plan::to_string(wire)));
        return std::nullopt;
    }
    return std::move(raw).value();
}

}  // namespace eip2mqtt::adapters::yaml::detail
