#include "eip2mqtt/core/redundancy/sample_window.hpp"

#include <algorithm>
#include <utility>

namespace eip2mqtt::core::redundancy {

WindowBounds window_bounds(std::chrono::milliseconds takeover, std::chrono::milliseconds period,
                           std::size_t max_bytes) {
    const auto span = 2 * takeover;
    const auto per_span = static_cast<std::size_t>(span / std::max(period, decltype(period){1}));
    const auto samples = std::clamp<std::size_t>(2 * per_span + 2, 16, max_window_samples);
    return {span, samples, max_bytes};
}

void SampleWindow::set_bounds(WindowBounds bounds, MonoTime now) {
    bounds_ = bounds;
    make_room(0, 0, now);
}

void SampleWindow::drop_oldest() {
    auto& oldest = samples_.front();
    bytes_ -= bytes_of(oldest.tags.size());
    if (oldest.tags.capacity() > spare_.capacity()) spare_ = std::move(oldest.tags);
    samples_.pop_front();
}

void SampleWindow::drop_expired(MonoTime now) {
    while (!samples_.empty() && now - samples_.front().arrived > bounds_.span) drop_oldest();
}

std::size_t SampleWindow::make_room(std::size_t samples, std::size_t bytes, MonoTime now) {
    drop_expired(now);
    std::size_t pushed_out = 0;
    while (!samples_.empty() && (samples_.size() + samples > bounds_.max_samples ||
                                 bytes_ + bytes > bounds_.max_bytes)) {
        drop_oldest();
        ++pushed_out;
    }
    return pushed_out;
}

std::size_t SampleWindow::record(const SampleKey& key, MonoTime now, std::int64_t timestamp_ms,
                                 quality::Quality quality, std::span<const plan::TagSample> tags) {
    const auto incoming = bytes_of(tags.size());
    const auto pushed_out = make_room(1, incoming, now);
    // A sample larger than the whole budget is not kept: the window stays empty rather than
    // over its bound.
    if (incoming > bounds_.max_bytes || bounds_.max_samples == 0) return pushed_out + 1;
    auto kept = std::move(spare_);
    spare_ = {};
    kept.assign(tags.begin(), tags.end());
    samples_.push_back({key, now, timestamp_ms, quality, std::move(kept)});
    bytes_ += incoming;
    return pushed_out;
}

ReplayStart SampleWindow::after(const std::optional<SampleKey>& watermark, MonoTime now) {
    drop_expired(now);
    if (!watermark) return {0, false};
    for (std::size_t i = samples_.size(); i-- > 0;) {
        if (samples_[i].key == *watermark) return {i + 1, true};
    }
    // Not one of the window's: the standby lost that datagram, or it is older than the span.
    for (std::size_t i = samples_.size(); i-- > 0;) {
        if (!comes_after(samples_[i].key, *watermark)) return {i + 1, false};
    }
    return {0, false};
}

}  // namespace eip2mqtt::core::redundancy
