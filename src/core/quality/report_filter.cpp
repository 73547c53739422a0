#include "eip2mqtt/core/quality/report_filter.hpp"

#include <cmath>
#include <variant>

namespace eip2mqtt::core::quality {
namespace {

// Deadband applies to numbers only: a bool or a text changes or it does not, and a NaN on
// either side makes the difference NaN, which would hide the change. An array moves when any
// element moves beyond the band.
bool moved(const plan::Value& now, const plan::Value& before, double deadband) {
    if (const auto* items = plan::list_items(now)) {
        const auto* old = plan::list_items(before);
        if (old == nullptr || old->size() != items->size()) return true;
        for (std::size_t i = 0; i < items->size(); ++i) {
            if (moved((*items)[i], (*old)[i], deadband)) return true;
        }
        return false;
    }
    if (deadband <= 0.0 || std::holds_alternative<bool>(now) || plan::is_composite(now)) {
        return !plan::same_value(now, before);
    }
    const double a = plan::to_double(now);
    const double b = plan::to_double(before);
    if (std::isnan(a) || std::isnan(b)) return !plan::same_value(now, before);
    if (a == b) return false;  // equal infinities: inf - inf is NaN
    return std::fabs(a - b) > deadband;
}

}  // namespace

bool ReportFilter::should_publish(const plan::Value& value, Quality quality, MonoTime now,
                                  double deadband, std::chrono::seconds refresh) const {
    if (!has_last()) return true;
    if (quality != quality_) return true;
    if (value.index() != value_.index()) return true;
    if (moved(value, value_, deadband)) return true;
    return refresh.count() > 0 && now - at_ >= refresh;
}

void ReportFilter::published(const plan::Value& value, Quality quality, MonoTime now) {
    value_ = value;
    quality_ = quality;
    at_ = now;
}

std::optional<MonoTime> ReportFilter::refresh_due(std::chrono::seconds refresh) const {
    if (!has_last() || refresh.count() <= 0) return std::nullopt;
    return at_ + refresh;
}

}  // namespace eip2mqtt::core::quality
