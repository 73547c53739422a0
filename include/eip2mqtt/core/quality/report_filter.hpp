#pragma once
/// Report by exception for one tag: publish when the value moves beyond the deadband, when the
/// quality changes, and at least every `refresh` (docs/mqtt-api.md "Tag values").

#include <chrono>
#include <optional>

#include "eip2mqtt/core/plan/value.hpp"
#include "eip2mqtt/core/quality/quality.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::quality {

/// A gateway holds one per consumed tag (100,000 in a large plant), so it keeps only the last
/// publication (32 bytes): the tag's deadband and refresh are passed in by the caller, who has
/// the tag's spec, rather than copied here.
class ReportFilter {
public:
    /// `deadband` is absolute (0 publishes any change); `refresh` <= 0 never republishes an
    /// unchanged value. True when (value, quality) must be published now. Does not record it:
    /// call published() once the publication was queued.
    bool should_publish(const plan::Value& value, Quality quality, MonoTime now, double deadband,
                        std::chrono::seconds refresh) const;

    /// Records what was published; deadband and refresh count from here.
    void published(const plan::Value& value, Quality quality, MonoTime now);

    /// Forgets the last publication, so the next value is published whatever it is (used after
    /// a reconnect or reload).
    void reset() { quality_ = never_published; }

    /// When a refresh every `refresh` of the last publication falls due; nullopt before the first
    /// one or when `refresh` <= 0.
    std::optional<MonoTime> refresh_due(std::chrono::seconds refresh) const;

    /// The last published value; nullptr before the first publication.
    const plan::Value* last_value() const { return has_last() ? &value_ : nullptr; }

private:
    // Not a Quality enumerator: it must never reach a payload. Stored in quality_ instead of
    // wrapping the last publication in std::optional, which would add 8 bytes of flag and padding.
    static constexpr auto never_published = static_cast<Quality>(0xff);

    bool has_last() const { return quality_ != never_published; }

    plan::Value value_;
    MonoTime at_{};
    Quality quality_ = never_published;
};

}  // namespace eip2mqtt::core::quality
