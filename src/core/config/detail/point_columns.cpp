// A point list's optional engineering columns: Units and the scaling a SCADA package exports.

#include "core/config/detail/point_columns.hpp"

#include <charconv>
#include <cmath>
#include <string>

namespace eip2mqtt::core::config::detail {
namespace {

constexpr std::array<std::string_view, 9> names{"units",        "scaletype",  "scalerawlow",
                                                "scalerawhigh", "scaleeulow", "scaleeuhigh",
                                                "clamp",        "count",      "length"};

std::optional<double> number(std::string_view text) {
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

/// A ScaleType: nullopt for none (empty or "None"), or the kind; `known` false when it is no
/// type we know.
std::optional<plan::ScaleKind> scale_kind(std::string_view text, bool& known) {
    known = true;
    if (text.empty() || equals_lower(text, "none")) return std::nullopt;
    if (equals_lower(text, "linear")) return plan::ScaleKind::linear;
    for (const std::string_view root : {"squareroot", "square root", "sqrt", "square_root"}) {
        if (equals_lower(text, root)) return plan::ScaleKind::square_root;
    }
    known = false;
    return std::nullopt;
}

std::optional<bool> flag(std::string_view text) {
    for (const std::string_view yes : {"true", "yes", "1", "y"}) {
        if (equals_lower(text, yes)) return true;
    }
    for (const std::string_view no : {"false", "no", "0", "n", ""}) {
        if (equals_lower(text, no)) return false;
    }
    return std::nullopt;
}

}  // namespace

void PointColumns::find(const std::vector<CsvField>& fields) {
    for (std::size_t c = 0; c < names.size(); ++c) {
        for (std::size_t i = 0; i < fields.size(); ++i) {
            if (equals_lower(fields[i].text, names[c])) index_[c] = i;
        }
    }
}

const CsvField* PointColumns::field(const std::vector<CsvField>& fields, Column column) const {
    const auto& i = index_[column];
    return i && *i < fields.size() ? &fields[*i] : nullptr;
}

bool PointColumns::read_count(const std::vector<CsvField>& fields, const Mark& at,
                              plan::TagSpec& tag, Diagnostics& errors) const {
    for (const Column c : {elements, length}) {
        const auto* f = field(fields, c);
        if (f == nullptr || f->text.empty()) continue;
        std::uint16_t n = 0;
        const auto [end, ec] = std::from_chars(f->text.data(), f->text.data() + f->text.size(), n);
        if (ec != std::errc{} || end != f->text.data() + f->text.size()) {
            errors.push_back({Mark{at.file, at.line, f->column},
                              "expected a count of 0..65535, not " + std::string(f->text)});
            return false;
        }
        tag.count = n;
    }
    return true;
}

bool PointColumns::read(const std::vector<CsvField>& fields, const Mark& at, plan::TagSpec& tag,
                        Diagnostics& errors) const {
    if (!read_count(fields, at, tag, errors)) return false;
    const auto text = [&](Column c) { return field(fields, c) ? field(fields, c)->text : ""; };
    const auto error = [&](Column c, std::string message) {
        errors.push_back({Mark{at.file, at.line, field(fields, c)->column}, std::move(message)});
        return false;
    };
    if (!text(units).empty()) tag.mutable_extras().unit = std::string(text(units));
    bool known = true;
    const auto kind = scale_kind(text(type), known);
    if (!known) {
        return error(type, "unknown ScaleType " + std::string(text(type)) +
                               " (expected None, Linear or SquareRoot)");
    }
    std::array<double, 4> ends{};
    int given = 0;
    for (const Column c : {raw_low, raw_high, eu_low, eu_high}) {
        if (text(c).empty()) continue;
        const auto value = number(text(c));
        if (!value) return error(c, "expected a number, not " + std::string(text(c)));
        ends[c - raw_low] = *value;
        ++given;
    }
    const auto clamped = flag(text(clamp));
    if (!clamped) return error(clamp, "expected true or false for Clamp");
    if (given == 0 && !kind) return true;  // not scaled
    if (given != 4) {
        // Reported at the first of the scale's columns the row has: one of them is set.
        for (const Column c : {type, raw_low, raw_high, eu_low, eu_high}) {
            if (field(fields, c)) {
                return error(c,
                             "a scale needs ScaleRawLow, ScaleRawHigh, ScaleEULow and "
                             "ScaleEUHigh");
            }
        }
    }
    tag.mutable_extras().scale = plan::Scaling{kind.value_or(plan::ScaleKind::linear),
                                               {ends[0], ends[1]},
                                               {ends[2], ends[3]},
                                               1.0,
                                               0.0,
                                               *clamped,
                                               std::nullopt};
    return true;
}

}  // namespace eip2mqtt::core::config::detail
