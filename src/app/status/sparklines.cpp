#include "eip2mqtt/app/status/sparklines.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <variant>

namespace eip2mqtt::app::status {
namespace {

constexpr float no_value = std::numeric_limits<float>::quiet_NaN();

/// The value as a point; NaN for a text or an array.
float point_of(const core::plan::Value& value) {
    return std::visit(
        [](const auto& v) -> float {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_arithmetic_v<V>) {
                return static_cast<float>(v);
            } else {
                return no_value;
            }
        },
        value);
}

bool plotted(const core::plan::TagPlan& tag) {
    return tag.spec.type != core::plan::TagType::string && !tag.spec.is_array();
}

}  // namespace

void Sparklines::exchanges_changed(const ExchangeSet& running, std::span<const std::string>) {
    std::unordered_map<const core::plan::ExchangePlan*, Slot> kept;
    tags_ = 0;
    for (const auto* plan : running.consumed) {
        auto found = slots_.find(plan);
        if (found != slots_.end()) {
            tags_ += found->second.values.size() / points;
            kept.emplace(plan, std::move(found->second));
        }
    }
    for (const auto* plan : running.consumed) {
        if (kept.contains(plan)) continue;
        Slot slot;
        slot.rows.assign(plan->tags.size(), no_row);
        std::uint32_t rows = 0;
        for (std::size_t i = 0; i < plan->tags.size() && tags_ + rows < max_tags; ++i) {
            if (plotted(plan->tags[i])) slot.rows[i] = rows++;
        }
        slot.values.assign(std::size_t{rows} * points, no_value);
        tags_ += rows;
        kept.emplace(plan, std::move(slot));
    }
    slots_ = std::move(kept);
}

void Sparklines::advance(Slot& slot, std::int64_t step) {
    const auto rows = slot.values.size() / points;
    if (slot.step >= 0 && step - slot.step >= static_cast<std::int64_t>(points)) {
        // A whole line or more later: every column takes the last value.
        const auto last = static_cast<std::size_t>(slot.step % points);
        for (std::size_t row = 0; row < rows; ++row) {
            const auto value = slot.values[row * points + last];
            std::fill_n(slot.values.begin() + static_cast<std::ptrdiff_t>(row * points), points,
                        value);
        }
    } else if (slot.step >= 0) {
        for (auto s = slot.step + 1; s <= step; ++s) {
            const auto to = static_cast<std::size_t>(s % points);
            const auto previous = static_cast<std::size_t>((s - 1) % points);
            for (std::size_t row = 0; row < rows; ++row) {
                slot.values[row * points + to] = slot.values[row * points + previous];
            }
        }
    }
    slot.step = step;
}

void Sparklines::tag_samples(const SampleBatch& batch) {
    const auto found = slots_.find(&batch.exchange);
    if (found == slots_.end() || found->second.values.empty()) return;
    auto& slot = found->second;
    // The gateway's clock, as the page's steps are: a producer's own clock may be off, or step
    // back.
    const auto step_now = clock_.wall_ms() / step.count();
    if (step_now > slot.step) advance(slot, step_now);
    const auto column = static_cast<std::size_t>(slot.step % points);
    for (const auto& sample : batch.samples) {
        if (sample.tag >= slot.rows.size() || slot.rows[sample.tag] == no_row) continue;
        slot.values[slot.rows[sample.tag] * points + column] = point_of(sample.value);
    }
}

void Sparklines::append_json(std::string& out, const core::plan::ExchangePlan& plan,
                             std::size_t tag, std::int64_t now_ms) const {
    const auto found = slots_.find(&plan);
    if (found == slots_.end() || tag >= found->second.rows.size()) return;
    const auto& slot = found->second;
    const auto row = slot.rows[tag];
    if (row == no_row) return;
    const auto newest = now_ms / step.count();
    out += R"(,"sparkline":[)";
    for (auto s = newest - static_cast<std::int64_t>(points) + 1; s <= newest; ++s) {
        if (s != newest - static_cast<std::int64_t>(points) + 1) out += ',';
        // Steps after the newest written carry its value; those a line before it are gone.
        const auto at = std::min(s, slot.step);
        const bool kept = at >= 0 && at > slot.step - static_cast<std::int64_t>(points);
        const float value =
            kept ? slot.values[std::size_t{row} * points + static_cast<std::size_t>(at % points)]
                 : no_value;
        if (std::isnan(value)) {
            out += "null";
        } else {
            fmt::format_to(std::back_inserter(out), "{:.7g}", value);
        }
    }
    out += ']';
}

}  // namespace eip2mqtt::app::status
