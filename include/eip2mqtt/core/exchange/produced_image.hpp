#pragma once
/// The image of one produced exchange: its data bytes, the request id counter, and the queue of
/// accepted writes waiting for the next production (docs/protocol.md §5). Writes are
/// applied only between two productions, whole batches at a time, so one datagram never
/// carries half a multi-tag write. Pure: time is passed in.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <span>
#include <vector>

#include "eip2mqtt/core/plan/exchange_plan.hpp"
#include "eip2mqtt/core/time.hpp"
#include "eip2mqtt/core/wire/header.hpp"
#include "eip2mqtt/core/write/write_validation.hpp"

namespace eip2mqtt::core::exchange {

class ProducedImage {
public:
    /// The request id of the first datagram after start-up. Consumers must not assume a start
    /// value (docs/protocol.md §2); 1 rather than 0 because some tools read 0 as "never sent".
    static constexpr std::uint16_t first_request_id = 1;
    /// A batch id above every other: produce() applies every staged batch.
    static constexpr std::uint64_t no_limit = ~std::uint64_t{0};

    /// Starts from `restored` when it has the plan's length, else from zeros with each tag's
    /// `initial` value applied. `max_pending` bounds the write queue (batches).
    ProducedImage(const plan::ExchangePlan& plan, std::span<const std::byte> restored,
                  std::size_t max_pending = 1024);

    /// Queues a validated batch for the next production; false when the queue is full. Batch
    /// ids must grow in staging order (the range arguments below rely on it).
    bool stage(write::WriteBatch batch);

    /// Builds the next datagram into `out` (at least 32 + length bytes): applies the staged
    /// batches whose id is at most `through`, every one by default (bits by read-modify-write
    /// of their byte), stamps the header (request id, `wall` as seconds + nanoseconds, status 0,
    /// the configured signature), then advances the request id (wrapping). Returns the datagram
    /// size. The ids of the batches this datagram is the first to carry are appended to
    /// `carried` (not cleared first), in staging order.
    std::size_t produce(WallTime wall, std::span<std::byte> out,
                        std::vector<std::uint64_t>& carried, std::uint64_t through = no_limit);

    /// The data as it will be once every staged batch is applied, in `out` (replaced); returns
    /// the id of the last staged batch, 0 when none is staged. Changes nothing: what a save
    /// ahead of the production writes.
    std::uint64_t project(std::vector<std::byte>& out) const;

    /// Drops every staged batch unapplied (its exchange stops for good: a reload changed or
    /// removed it); their ids are appended to `dropped` (not cleared first), in staging order.
    void discard_pending(std::vector<std::uint64_t>& dropped);
    /// Takes every staged batch out unapplied (a pair's leader steps down: another unit settles
    /// them), appended to `taken` in staging order.
    void take_pending(std::vector<write::WriteBatch>& taken);
    /// Drops the staged batches whose id lies in (`after`, `through`], the others stay queued.
    void discard_pending(std::uint64_t after, std::uint64_t through,
                         std::vector<std::uint64_t>& dropped);

    /// A hot-standby pair: the standby takes the leader's image as its own (the plan's length;
    /// another size is ignored), the staged batches staying queued over it. Returns whether a
    /// byte changed. Not dirty: nothing was produced, and the standby reports nothing north.
    bool adopt(std::span<const std::byte> data);
    /// A hot-standby pair: the next datagram takes the request id after `heard`, the last one
    /// the standby heard from the leader's producer of this exchange.
    void continue_after(std::uint16_t heard);

    /// Whether the data already holds every value of `writes`: applying them would change no
    /// byte. What a new leader of a pair asks of a write its old leader left unanswered.
    bool holds(std::span<const write::TagWrite> writes) const;

    /// The data bytes as they stand (the last produced values plus nothing staged).
    std::span<const std::byte> data() const { return data_; }
    /// True when produce() changed the data since the last call to clear_dirty().
    bool dirty() const { return dirty_; }
    void clear_dirty() { dirty_ = false; }
    /// True when data was restored rather than initialised.
    bool restored() const { return restored_; }
    std::size_t pending() const { return pending_.size(); }
    std::uint16_t next_request_id() const { return request_id_; }

private:
    /// Applies `batch` to `data`; true when a byte changed.
    bool apply(const write::WriteBatch& batch, std::span<std::byte> data) const;

    const plan::ExchangePlan* plan_;
    std::vector<std::byte> data_;
    std::deque<write::WriteBatch> pending_;
    std::size_t max_pending_;
    std::uint16_t request_id_ = first_request_id;
    bool dirty_ = false;
    bool restored_ = false;
};

}  // namespace eip2mqtt::core::exchange
