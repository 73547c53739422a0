#pragma once
// A fake HistorySink (where store and forward replays the journal): it keeps what it is handed,
// for integer tags.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "eip2mqtt/app/history/history_sink.hpp"

namespace eip2mqtt::test {

/// One batch as the sink was handed it, its samples as (tag, integer value).
struct Replayed {
    std::string exchange;
    core::quality::Quality quality;
    std::int64_t timestamp_ms;
    std::vector<std::pair<std::size_t, std::int64_t>> samples;
    std::uint64_t token;
};

/// Keeps each replayed batch, in order.
class RecordingHistorySink final : public app::history::HistorySink {
public:
    bool replay(const app::SampleBatch& batch, std::uint64_t ack_token) override {
        if (good_only && batch.quality != core::quality::Quality::good) return false;
        Replayed r{batch.exchange.spec.name, batch.quality, batch.timestamp_ms, {}, ack_token};
        for (const auto& s : batch.samples) {
            r.samples.emplace_back(s.tag, std::get<std::int64_t>(s.value));
        }
        replayed.push_back(std::move(r));
        return true;
    }
    std::vector<Replayed> replayed;
    bool good_only = false;  ///< as the Sparkplug node: history of good samples only
};

}  // namespace eip2mqtt::test
