#include "adapters/mqtt/detail/outbox.hpp"

#include <algorithm>
#include <string>

namespace eip2mqtt::adapters::mqtt::detail {

Outbox::Outbox(std::size_t capacity, std::size_t batch_capacity, bool batch_first)
    : queue_(capacity), batch_queue_(batch_capacity), batch_first_(batch_first) {}

void Outbox::push(Message& message) {
    (message.batch_lane ? batch_queue_ : queue_).push(std::move(message));
    // Queued whole, so no buffer came back: give the caller a spare to fill next time.
    const std::size_t inline_capacity = std::string().capacity();
    if (message.topic.capacity() <= inline_capacity &&
        message.payload.capacity() <= inline_capacity && !spares_.empty()) {
        message = std::move(spares_.back());
        spares_.pop_back();
    }
    backlog_peak_ = std::max(backlog_peak_, queue_.size());
}

bool Outbox::next_is_batch() const {
    return batch_queue_.empty() ? false : batch_first_ || queue_.empty() || next_from_batch_;
}

bool Outbox::take_next(Message& message) {
    const bool from_batch = next_is_batch();
    if (!batch_queue_.empty() && !queue_.empty()) next_from_batch_ = !next_from_batch_;
    auto next = (from_batch ? batch_queue_ : queue_).pop();
    if (!next) return false;
    message = std::move(*next);
    return true;
}

const Message* Outbox::peek_next() const {
    return (next_is_batch() ? batch_queue_ : queue_).oldest();
}

void Outbox::recycle(Message&& message, std::size_t keep) {
    // More spares than a window's worth only hold memory after an overload; a drained
    // backlog's others are freed.
    if (spares_.size() >= keep) return;
    message.clear();
    spares_.push_back(std::move(message));
}

std::size_t Outbox::discard_all() {
    std::size_t count = 0;
    for (auto* lane : {&queue_, &batch_queue_}) {
        while (lane->pop()) ++count;
    }
    return count;
}

bool Outbox::release_after_backlog(std::size_t threshold) {
    if (!empty() || backlog_peak_ < threshold) return false;
    backlog_peak_ = 0;
    queue_.release_memory();
    batch_queue_.release_memory();
    return true;
}

}  // namespace eip2mqtt::adapters::mqtt::detail
