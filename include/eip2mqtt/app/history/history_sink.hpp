#pragma once
/// Where store and forward (app/history/store_and_forward) hands the samples it replays: a
/// northbound that can publish history (the JSON tree's `_history`, the Sparkplug node's
/// historical DDATA).

#include <cstdint>

#include "eip2mqtt/app/northbound/northbound.hpp"

namespace eip2mqtt::app::history {

/// Where replayed samples go.
class HistorySink {
public:
    virtual ~HistorySink() = default;
    /// Publishes `batch` as history; the publication carries `ack_token`, which must come back
    /// to StoreAndForward once the broker acknowledged it. False: this sink has no use for the
    /// batch (nothing was published, nothing will be acknowledged).
    virtual bool replay(const SampleBatch& batch, std::uint64_t ack_token) = 0;
};

}  // namespace eip2mqtt::app::history
