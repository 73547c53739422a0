#pragma once
/// The last 10 minutes of each numeric tag of the consumed exchanges, for the status page's
/// sparklines (docs/operations.md, "Status page and API"): one point per 10 s, the tag's value
/// at the end of that step, 60 points. A step in which the tag did not change keeps its value
/// (the exchanges report by exception). Memory is bounded: 60 floats (240 B) per tag kept, for
/// at most max_tags tags, given to the exchanges in configuration order; those beyond have none.
///
/// It is a northbound of the exchanges' fan-out, so it sees what goes north: while a pair's unit
/// stands by, its sparklines pause.
///
/// Threading: the loop only.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/app/northbound/northbound.hpp"
#include "eip2mqtt/core/clock.hpp"

namespace eip2mqtt::app::status {

class Sparklines final : public Northbound {
public:
    /// `clock` (the steps' time) must outlive it.
    explicit Sparklines(const core::Clock& clock) : clock_(clock) {}

    static constexpr std::size_t points = 60;
    static constexpr std::chrono::milliseconds step{10'000};
    /// Tags given a sparkline, over every exchange: 6 MB at most.
    static constexpr std::size_t max_tags = 25'000;

    /// Kept exchanges keep their points; new ones get rows while the bound allows.
    void exchanges_changed(const ExchangeSet& running,
                           std::span<const std::string> retired_topics) override;
    void tag_samples(const SampleBatch& batch) override;

    /// `,"sparkline":[…]` for tag `tag` of `plan` at `now_ms`: the last `points` steps, oldest
    /// first, null where it had no value yet; nothing when the tag has no sparkline.
    void append_json(std::string& out, const core::plan::ExchangePlan& plan, std::size_t tag,
                     std::int64_t now_ms) const;
    /// Tags given a sparkline now.
    std::size_t tags() const { return tags_; }

private:
    static constexpr std::uint32_t no_row = UINT32_MAX;
    struct Slot {
        std::vector<std::uint32_t> rows;  ///< per tag of the plan: its row, or no_row
        std::vector<float> values;        ///< row * points + step % points; NaN: no value
        std::int64_t step = -1;           ///< of the newest column written; -1: none yet
    };
    /// Moves `slot` on to `step`, each step between taking the value of the one before.
    static void advance(Slot& slot, std::int64_t step);

    const core::Clock& clock_;
    std::unordered_map<const core::plan::ExchangePlan*, Slot> slots_;
    std::size_t tags_ = 0;
};

}  // namespace eip2mqtt::app::status
