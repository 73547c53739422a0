#pragma once
/// What waits to be sent, and the buffers that come back: the per-tag lane and batch mode's
/// `_values` lane (each a PublishQueue, served in turn when both wait, so that neither starves
/// the other, unless the batch lane is to go first), and the spare messages of completed
/// publications, handed back to publish()'s callers to fill again: otherwise the loop allocates two
/// strings per publication that Paho's thread then frees, and malloc's cross-thread traffic takes
/// much of the loop's time.
///
/// Threading: none of its own; the Sender guards it, in its SendLedger, with its mutex.

#include <cstddef>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/adapters/mqtt/publish_queue.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

class Outbox {
public:
    /// `batch_first`: the batch lane goes first whenever both wait, instead of in turn.
    Outbox(std::size_t capacity, std::size_t batch_capacity, bool batch_first = false);

    /// Queues `message` in its lane. Leaves it blank with buffers to fill again: those of the
    /// message it replaced, or a spare when it was queued whole.
    void push(Message& message);
    /// The next message, from the two lanes in turn; false when both are empty.
    bool take_next(Message& message);
    /// The message take_next would take, left in place; nullptr when both lanes are empty.
    const Message* peek_next() const;
    /// Keeps the buffers of a completed publication for a later push, up to `keep` spares (a
    /// window's worth is what cycles; more only held memory after an overload).
    void recycle(Message&& message, std::size_t keep);

    /// Drops everything queued (a session-bound client's connection went); returns how many.
    std::size_t discard_all();

    bool empty() const { return queue_.empty() && batch_queue_.empty(); }
    std::size_t size() const { return queue_.size() + batch_queue_.size(); }
    /// After a backlog of at least `threshold` messages has drained, frees what the queues kept
    /// sized for it and returns true (time for malloc_trim); false otherwise.
    bool release_after_backlog(std::size_t threshold);

    const PublishQueue& tags() const { return queue_; }
    const PublishQueue& batch() const { return batch_queue_; }
    void set_capacity(std::size_t capacity) { queue_.set_capacity(capacity); }
    void set_batch_first(bool batch_first) { batch_first_ = batch_first; }

private:
    /// Whose turn it is: the batch lane when only it waits, or when both wait and it is its turn.
    bool next_is_batch() const;

    PublishQueue queue_;
    PublishQueue batch_queue_;
    bool batch_first_;
    bool next_from_batch_ = false;  ///< whose turn when both lanes wait (not batch_first_)
    std::vector<Message> spares_;
    std::size_t backlog_peak_ = 0;  ///< largest queue since memory was last given back
};

}  // namespace eip2mqtt::adapters::mqtt::detail
