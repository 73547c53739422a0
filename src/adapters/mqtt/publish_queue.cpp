#include "eip2mqtt/adapters/mqtt/publish_queue.hpp"

#include <utility>

namespace eip2mqtt::adapters::mqtt {

PublishQueue::PublishQueue(std::size_t capacity) : capacity_(capacity) {}

void PublishQueue::push(Message message) {
    if (message.coalesce) {
        if (auto it = by_topic_.find(message.topic); it != by_topic_.end()) {
            // Same topic: everything but the topic is replaced, so the key (a view of the
            // queued message's topic) stays valid.
            Message& queued = slots_[it->second - sequence_base_];
            queued.payload = std::move(message.payload);
            queued.qos = message.qos;
            queued.retain = message.retain;
            queued.correlation_data = std::move(message.correlation_data);
            queued.batch_lane = message.batch_lane;
            ++coalesced_;
            return;
        }
    } else {
        // A newer value queued after a non-coalescing message must not jump ahead of it by
        // replacing an older slot, or the topic would end on a stale value.
        by_topic_.erase(message.topic);
    }
    if (capacity_ == 0) {
        ++dropped_overflow_;
        return;
    }
    while (slots_.size() >= capacity_) {
        drop_oldest();
    }
    const std::uint64_t sequence = sequence_base_ + slots_.size();
    slots_.push_back(std::move(message));
    if (slots_.back().coalesce) {
        // A deque never moves its elements on push_back or pop_front: the view stays valid
        // until this slot leaves, which erases it first.
        by_topic_.emplace(slots_.back().topic, sequence);
    }
}

std::optional<Message> PublishQueue::pop() {
    if (slots_.empty()) {
        return std::nullopt;
    }
    if (auto it = by_topic_.find(slots_.front().topic);
        it != by_topic_.end() && it->second == sequence_base_) {
        by_topic_.erase(it);  // before the topic it views moves away
    }
    Message message = std::move(slots_.front());
    slots_.pop_front();
    ++sequence_base_;
    return message;
}

void PublishQueue::set_capacity(std::size_t capacity) {
    capacity_ = capacity;
    while (slots_.size() > capacity_) {
        drop_oldest();
    }
}

void PublishQueue::release_memory() {
    if (!slots_.empty()) return;
    // Swapped with a new map: neither clear() nor erasing gives buckets back.
    std::unordered_map<std::string_view, std::uint64_t>().swap(by_topic_);
    slots_.shrink_to_fit();
}

void PublishQueue::drop_oldest() {
    if (pop()) {
        ++dropped_overflow_;
    }
}

}  // namespace eip2mqtt::adapters::mqtt
