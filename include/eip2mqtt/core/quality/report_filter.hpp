#pragma once
/// Report by exception for one tag: publish when the value moves beyond the deadband, when the
/// quality changes, and at least every `refresh` (product.md "MQTT").

#include <chrono>
#include <optional>

#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/quality/quality.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::quality {

class ReportFilter {
public:
    ReportFilter(double deadband, std::chrono::seconds refresh)
        : deadband_(deadband), refresh_(refresh) {}

    /// True when (value, quality) must be published now. Does not record it: call published()
    /// once the publication was queued.
    bool should_publish(const plan::Value& value, Quality quality, MonoTime now) const;

    /// Records what was published; deadband and refresh count from here.
    void published(const plan::Value& value, Quality quality, MonoTime now);

    /// Forgets the last publication, so the next value is published whatever it is (used after
    /// a reconnect or reload).
    void reset() { last_.reset(); }

    /// When the refresh of the last publication falls due; nullopt before the first one.
    std::optional<MonoTime> refresh_due() const;

    /// The last published value; nullptr before the first publication.
    const plan::Value* last_value() const { return last_ ? &last_->value : nullptr; }

private:
    struct Last {
        plan::Value value;
        Quality quality;
        MonoTime at;
    };
    double deadband_;
    std::chrono::seconds refresh_;
    std::optional<Last> last_;
};

}  // namespace eip2mqtt::core::quality
