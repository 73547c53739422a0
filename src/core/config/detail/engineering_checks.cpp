// The checks of a tag's scale and percent deadband.

#include "core/config/detail/engineering_checks.hpp"

#include <cmath>

#include "eip2mqtt/core/plan/scaling.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::core::config::detail {
namespace {

using plan::ScaleKind;
using plan::ScaleRange;

std::string range_text(const ScaleRange& r) { return number_text(r.lo) + ".." + number_text(r.hi); }

bool finite(const ScaleRange& r) { return std::isfinite(r.lo) && std::isfinite(r.hi); }

void check_ranges(const TagConfig& tag, const plan::Scaling& s,
                  const std::function<std::string()>& what, Diagnostics& out) {
    const auto& marks = tag.marks;
    if (!finite(s.raw)) {
        out.push_back({marks.of("scale.raw"), what() + ": scale raw ends must be finite numbers"});
    } else if (s.raw.lo == s.raw.hi) {
        out.push_back({marks.of("scale.raw"), what() + ": scale raw ends are equal (" +
                                                  range_text(s.raw) + "): no span to scale from"});
    } else if (s.kind == ScaleKind::square_root && (s.raw.lo < 0 || s.raw.hi < 0)) {
        out.push_back(
            {marks.of("scale.raw"), what() + ": a square-root scale takes raw ends of 0 or more (" +
                                        range_text(s.raw) + "): a negative count has no root"});
    }
    if (!finite(s.eu)) {
        out.push_back({marks.of("scale.eu"), what() + ": scale eu ends must be finite numbers"});
    } else if (s.eu.lo == s.eu.hi) {
        out.push_back({marks.of("scale.eu"),
                       what() + ": scale eu ends are equal (" + range_text(s.eu) +
                           "): every raw value would read the same, and writes have no raw form"});
    }
}

void check_scale(const TagConfig& tag, const std::function<std::string()>& what, Diagnostics& out) {
    const auto& s = *tag.spec.scale();
    const auto& marks = tag.marks;
    if (tag.spec.type == plan::TagType::bit || tag.spec.type == plan::TagType::string) {
        const std::string type(plan::to_string(tag.spec.type));
        out.push_back(
            {marks.of("scale"), what() + " is a " + type + ": a " + type + " has no scale"});
        return;
    }
    if (s.kind != ScaleKind::gain_offset) {
        check_ranges(tag, s, what, out);
        return;
    }
    if (!std::isfinite(s.gain) || s.gain == 0) {
        out.push_back({marks.of("scale.gain"),
                       what() + ": scale gain " + number_text(s.gain) +
                           " must be a finite number other than 0 (writes divide by it)"});
    }
    if (!std::isfinite(s.offset)) {
        out.push_back({marks.of("scale.offset"), what() + ": scale offset must be finite"});
    }
}

}  // namespace

std::string number_text(double value) {
    std::string text = std::to_string(value);
    if (text.find('.') != std::string::npos) {
        text.erase(text.find_last_not_of('0') + 1);
        if (text.back() == '.') text.pop_back();
    }
    return text;
}

std::string outside_eu_range(const plan::Scaling& scale, double value) {
    const auto span = plan::eu_span(scale);
    if (!span || (value >= span->lo && value <= span->hi)) return {};
    return " is outside the engineering range " + range_text(*span);
}

void check_shape(const TagConfig& tag, const std::function<std::string()>& what, Diagnostics& out) {
    const auto& spec = tag.spec;
    const auto& marks = tag.marks;
    // A point list's row has no keys: its Count and Length columns are both the count.
    const bool from_yaml = !marks.keys.empty();
    if (spec.type == plan::TagType::string) {
        if (marks.contains("count")) {
            out.push_back({marks.of("count"), what() + " is a string: it takes length, not count"});
        } else if (spec.count == 0 || (from_yaml && !marks.contains("length"))) {
            out.push_back({marks.of("length"), what() + " is a string of no bytes: give it a "
                                                        "length of 1 or more"});
        }
        for (const auto* key : {"min", "max", "deadband"}) {
            if (marks.contains(key)) {
                out.push_back({marks.of(key), what() + " is a string: it has no " + key});
            }
        }
        return;
    }
    if (marks.contains("length")) {
        out.push_back(
            {marks.of("length"), what() + ": only a string has a length (an array has a count)"});
    }
    if (!marks.contains("count") && spec.count == 1) return;
    // Bits take one bit each: 8 to a byte.
    const std::size_t most = spec.type == plan::TagType::bit
                                 ? 8 * wire::max_data_size
                                 : wire::max_data_size / plan::size_of(spec.type);
    if (spec.count == 0 || (spec.count < 2 && from_yaml)) {
        out.push_back({marks.of("count"), what() + " has count " + std::to_string(spec.count) +
                                              ": an array has 2 elements or more (leave count "
                                              "out for one value)"});
    } else if (spec.count > most) {
        out.push_back({marks.of("count"), what() + " has count " + std::to_string(spec.count) +
                                              ": at most " + std::to_string(most) + " of " +
                                              std::string(plan::to_string(spec.type)) +
                                              " fit an exchange"});
    }
}

void check_engineering(const TagConfig& tag, const std::function<std::string()>& what,
                       Diagnostics& out) {
    const auto& spec = tag.spec;
    check_shape(tag, what, out);
    if (spec.scale()) check_scale(tag, what, out);
    const auto& percent = spec.deadband_percent();
    if (!percent) return;
    if (!std::isfinite(*percent) || *percent < 0) {
        out.push_back({tag.marks.of("deadband.percent"),
                       what() + " has a deadband percent that is not 0 or more"});
    } else if (!(spec.scale() && plan::eu_span(*spec.scale())) && !(spec.min() && spec.max())) {
        out.push_back({tag.marks.of("deadband"),
                       what() + " has a percent deadband but no span to take it of: give it a "
                                "scale with eu, or min and max"});
    }
}

}  // namespace eip2mqtt::core::config::detail
