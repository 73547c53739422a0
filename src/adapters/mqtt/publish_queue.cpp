#include "eip2mqtt/adapters/mqtt/publish_queue.hpp"

#include <utility>

namespace eip2mqtt::adapters::mqtt {
namespace {

/// Spare index nodes kept: enough for the window of publications that cycle through the queue;
/// a drained backlog's others are freed.
constexpr std::size_t kMaxSpareNodes = 1024;

}  // namespace

PublishQueue::PublishQueue(std::size_t capacity) : capacity_(capacity) {}

void PublishQueue::push(Message&& message) {
    if (message.coalesce) {
        if (auto it = by_topic_.find(message.topic); it != by_topic_.end()) {
            // Same topic: everything but the topic is replaced, so the key (a view of the
            // queued message's topic) stays valid. Swapped, not assigned: the replaced
            // payload's buffer goes back to the caller instead of to malloc.
            Message& queued = slots_[it->second - sequence_base_];
            std::swap(queued.payload, message.payload);
            std::swap(queued.correlation_data, message.correlation_data);
            queued.qos = message.qos;
            queued.retain = message.retain;
            queued.batch_lane = message.batch_lane;
            ++coalesced_;
            message.clear();
            return;
        }
    } else if (auto it = by_topic_.find(message.topic); it != by_topic_.end()) {
        // A newer value queued after a non-coalescing message must not jump ahead of it by
        // replacing an older slot, or the topic would end on a stale value.
        unindex(it);
    }
    if (capacity_ == 0) {
        ++dropped_overflow_;
        message.clear();
        return;
    }
    while (slots_.size() >= capacity_) {
        drop_oldest();
    }
    const std::uint64_t sequence = sequence_base_ + slots_.size();
    const bool coalesce = message.coalesce;
    if (slots_.push_back(std::move(message))) {
        reindex();  // the ring grew: every queued topic moved
    }
    message.clear();  // moved from: valid but unspecified until cleared
    if (coalesce) index(slots_.back().topic, sequence);
}

std::optional<Message> PublishQueue::pop() {
    if (slots_.empty()) {
        return std::nullopt;
    }
    if (auto it = by_topic_.find(slots_.front().topic);
        it != by_topic_.end() && it->second == sequence_base_) {
        unindex(it);  // before the topic it views moves away
    }
    std::optional<Message> message(std::move(slots_.front()));
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
    Index().swap(by_topic_);
    std::vector<Index::node_type>().swap(spare_nodes_);
    slots_.release();
}

void PublishQueue::drop_oldest() {
    if (pop()) {
        ++dropped_overflow_;
    }
}

void PublishQueue::index(std::string_view topic, std::uint64_t sequence) {
    if (spare_nodes_.empty()) {
        by_topic_.emplace(topic, sequence);
        return;
    }
    auto node = std::move(spare_nodes_.back());
    spare_nodes_.pop_back();
    node.key() = topic;
    node.mapped() = sequence;
    by_topic_.insert(std::move(node));
}

void PublishQueue::unindex(Index::iterator it) {
    auto node = by_topic_.extract(it);
    if (spare_nodes_.size() < kMaxSpareNodes) spare_nodes_.push_back(std::move(node));
}

void PublishQueue::reindex() {
    // Each indexed sequence still names its slot: point its key at that slot's moved topic.
    // Only when the ring grows, which is when the queue passes its largest size so far.
    std::vector<Index::node_type> nodes;
    nodes.reserve(by_topic_.size());
    while (!by_topic_.empty()) nodes.push_back(by_topic_.extract(by_topic_.begin()));
    for (auto& node : nodes) {
        node.key() = slots_[node.mapped() - sequence_base_].topic;
        by_topic_.insert(std::move(node));
    }
}

}  // namespace eip2mqtt::adapters::mqtt
