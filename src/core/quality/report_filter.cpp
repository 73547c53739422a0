#include "eip2mqtt/core/quality/report_filter.hpp"

#include <cmath>
#include <variant>

namespace eip2mqtt::core::quality {
namespace {

// Deadband applies to numbers only: a bool changes or it does not, and a NaN on either side
// makes the difference NaN, which would hide the change.
bool moved(const plan::Value& now, const plan::Value& before, double deadband) {
    if (deadband <= 0.0 || std::holds_alternative<bool>(now)) {
        return !plan::same_value(now, before);
    }
    const double a = plan::to_double(now);
    const double b = plan::to_double(before);
    if (std::isnan(a) || std::isnan(b)) return !plan::same_value(now, before);
    if (a == b) return false;  // equal infinities: inf - inf is NaN
    return std::fabs(a - b) > deadband;
}

}  // namespace

bool ReportFilter::should_publish(const plan::Value& value, Quality quality, MonoTime now) const {
    if (!last_) return true;
    if (quality != last_->quality) return true;
    if (value.index() != last_->value.index()) return true;
    if (moved(value, last_->value, deadband_)) return true;
    return refresh_.count() > 0 && now - last_->at >= refresh_;
}

void ReportFilter::published(const plan::Value& value, Quality quality, MonoTime now) {
    last_ = Last{value, quality, now};
}

std::optional<MonoTime> ReportFilter::refresh_due() const {
    if (!last_ || refresh_.count() <= 0) return std::nullopt;
    return last_->at + refresh_;
}

}  // namespace eip2mqtt::core::quality
