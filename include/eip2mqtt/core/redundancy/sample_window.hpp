#pragma once
/// The standby's memory of a consumed exchange's last samples (docs/redundancy.md): every
/// sample the exchange reported, in the order it reported them, for a bounded time, so that
/// after a takeover the new leader can publish on `_history` those its leader had not had
/// acknowledged (`after`). Pure: the time is passed in.
///
/// Bounded three ways: by age (`span`, twice the takeover: a takeover comes `takeover` after
/// the leader was last heard, and its watermark is a little older still), by count (enough for
/// the span at the exchange's period, twice over for jitter and bursts) and by bytes (a share
/// of one budget for every exchange). A sample pushed out by count or bytes before it is `span`
/// old is counted: a takeover then may miss samples.
///
/// Threading: one thread (the loop).

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "eip2mqtt/core/plan/tag_sample.hpp"
#include "eip2mqtt/core/quality/quality.hpp"
#include "eip2mqtt/core/redundancy/sample_key.hpp"
#include "eip2mqtt/core/ring.hpp"
#include "eip2mqtt/core/time.hpp"

namespace eip2mqtt::core::redundancy {

/// One sample as the exchange reported it.
struct WindowedSample {
    SampleKey key;
    MonoTime arrived{};
    std::int64_t timestamp_ms = 0;  ///< the one its publication carries
    quality::Quality quality = quality::Quality::good;
    std::vector<plan::TagSample> tags;  ///< those reported (changed, or every one)
};

struct WindowBounds {
    std::chrono::milliseconds span{0};
    std::size_t max_samples = 0;
    std::size_t max_bytes = 0;
};

/// The most samples one window holds, whatever the period: fewer than half the request ids, so
/// one request id never names two samples of a window.
inline constexpr std::size_t max_window_samples = 16384;

/// The bounds of the window of an exchange of period `period` in a pair of takeover `takeover`,
/// with `max_bytes` its share of the byte budget: twice the takeover, and twice the samples that
/// span holds at the period (at least 16, at most max_window_samples).
WindowBounds window_bounds(std::chrono::milliseconds takeover, std::chrono::milliseconds period,
                           std::size_t max_bytes);

/// Where the samples to replay begin, and how that was found.
struct ReplayStart {
    std::size_t first = 0;  ///< index of the first sample newer than the watermark
    /// The watermark names a sample of the window; otherwise the samples newer by comes_after
    /// (none given, or the standby did not receive that datagram, or it is older than the span).
    bool watermark_found = false;
};

class SampleWindow {
public:
    explicit SampleWindow(WindowBounds bounds) : bounds_(bounds) {}

    /// New bounds (a reload changed the share of the budget); samples beyond them go at once.
    void set_bounds(WindowBounds bounds, MonoTime now);
    const WindowBounds& bounds() const { return bounds_; }

    /// Records a sample the exchange reported at `now`. Returns how many samples the count or
    /// byte bound pushed out before they were `span` old.
    std::size_t record(const SampleKey& key, MonoTime now, std::int64_t timestamp_ms,
                       quality::Quality quality, std::span<const plan::TagSample> tags);

    /// Drops the samples older than the span at `now`, then says where those newer than
    /// `watermark` begin: after the sample it names, or, when the window holds none by that
    /// name, after the newest sample not newer by comes_after. Every sample without one.
    ReplayStart after(const std::optional<SampleKey>& watermark, MonoTime now);

    std::size_t size() const { return samples_.size(); }
    const WindowedSample& operator[](std::size_t i) const { return samples_[i]; }
    std::size_t bytes() const { return bytes_; }

    /// What one sample of `tags` tags counts against the byte bound.
    static std::size_t bytes_of(std::size_t tags) {
        return sizeof(WindowedSample) + tags * sizeof(plan::TagSample);
    }

private:
    /// Drops the oldest sample; its tag vector is kept for the next record (no allocation on
    /// the data path once the window is full).
    void drop_oldest();
    void drop_expired(MonoTime now);
    /// Drops the expired samples, then pushes out the oldest until `samples` more samples of
    /// `bytes` fit; returns how many it pushed out.
    std::size_t make_room(std::size_t samples, std::size_t bytes, MonoTime now);

    WindowBounds bounds_;
    Ring<WindowedSample> samples_;
    std::size_t bytes_ = 0;
    std::vector<plan::TagSample> spare_;
};

}  // namespace eip2mqtt::core::redundancy
