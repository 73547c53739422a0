#include "eip2mqtt/core/exchange/save_then_answer.hpp"

#include <algorithm>
#include <utility>

namespace eip2mqtt::core::exchange {

std::optional<std::span<const std::byte>> SaveThenAnswer::request(const ProducedImage& image) {
    if (in_flight_) {
        again_ = true;
        return std::nullopt;
    }
    again_ = false;
    in_flight_ = true;
    saving_.swap(unsaved_);
    unsaved_.clear();
    saving_through_ = image.project(projection_);
    return std::span<const std::byte>(projection_);
}

SaveThenAnswer::Sent SaveThenAnswer::on_sent(std::span<const std::uint64_t> carried, bool changed) {
    const auto ahead = std::find_if(carried.begin(), carried.end(),
                                    [&](std::uint64_t id) { return id > saved_through_; });
    const std::span waiting(ahead, carried.end());
    if ((changed && saved_) || (!waiting.empty() && (in_flight_ || again_))) {
        unsaved_.insert(unsaved_.end(), waiting.begin(), waiting.end());
        return {std::span(carried.begin(), ahead), true};
    }
    return {carried, false};
}

SaveThenAnswer::Saved SaveThenAnswer::on_saved(const std::optional<std::string>& error) {
    in_flight_ = false;
    Saved saved;
    saved.answered = std::move(saving_);
    saving_.clear();
    if (error) {
        saved_ = false;
        retry_at_.reset();
        saved.refuse_after = saved_through_;
        saved.refuse_through = saving_through_;
        saved.status_changed = *error != error_;
        error_ = *error;
    } else {
        saved_through_ = std::max(saved_through_, saving_through_);
        saved.status_changed = !saved_;
        saved_ = true;
        saved.recovered = !error_.empty();
        error_.clear();
    }
    return saved;
}

bool SaveThenAnswer::on_tick(MonoTime now) {
    if (saved_ || in_flight_) return false;
    if (!retry_at_) {
        retry_at_ = now + retry_interval;
        return false;
    }
    if (now < *retry_at_) return false;
    retry_at_.reset();
    return true;
}

}  // namespace eip2mqtt::core::exchange
