#pragma once
/// The gateway's own bounded publication queue, instead of Paho's unbounded one: latest value
/// wins per topic (a newer message replaces an unsent older one in place), and when full the
/// oldest message is dropped. Both are counted (spdlog's overrun_oldest policy, for MQTT).
/// Single-threaded: the loop owns it.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "eip2mqtt/adapters/mqtt/message.hpp"
#include "eip2mqtt/core/ring.hpp"

namespace eip2mqtt::adapters::mqtt {

class PublishQueue {
public:
    explicit PublishQueue(std::size_t capacity);

    /// Queues `message`, replacing a queued one of the same topic when both coalesce. Leaves in
    /// `message` what the queue did not keep, blank (Message::clear()): the replaced payload's
    /// buffer and the topic's when it coalesced, nothing when it was queued anew. A caller that
    /// publishes in a loop fills it again without allocating.
    void push(Message&& message);

    /// Takes the oldest message; nullopt when empty.
    std::optional<Message> pop();
    /// The message pop() would take, left in place; nullptr when empty.
    const Message* oldest() const { return slots_.empty() ? nullptr : &slots_[0]; }

    std::size_t size() const { return slots_.size(); }
    bool empty() const { return slots_.empty(); }
    std::size_t capacity() const { return capacity_; }
    void set_capacity(std::size_t capacity);
    /// When empty, frees what a drained backlog left sized for its peak: the topic index keeps
    /// its bucket array (8 bytes a bucket, ~100,000 after every tag's first publication) and
    /// the ring its slots. Call it before malloc_trim; a no-op while messages wait.
    void release_memory();
    std::size_t index_buckets_for_test() const { return by_topic_.bucket_count(); }

    std::uint64_t dropped_overflow() const { return dropped_overflow_; }  ///< oldest dropped
    std::uint64_t coalesced() const { return coalesced_; }  ///< replaced by a newer value

private:
    using Index = std::unordered_map<std::string_view, std::uint64_t>;

    void drop_oldest();
    void index(std::string_view topic, std::uint64_t sequence);
    void unindex(Index::iterator it);
    void reindex();

    std::size_t capacity_;
    std::uint64_t sequence_base_ = 0;  ///< sequence number of slots_.front()
    core::Ring<Message> slots_;
    /// topic (a view of the queued message's own topic, so no copy) -> sequence number of its
    /// queued coalescing message. A message is replaced in place only by a newer one, so
    /// slots_ stays in order and never has holes.
    Index by_topic_;
    /// Index nodes of messages that left, reused for the next ones: a node per queued message
    /// was a malloc and a free per publication.
    std::vector<Index::node_type> spare_nodes_;
    std::uint64_t dropped_overflow_ = 0;
    std::uint64_t coalesced_ = 0;
};

}  // namespace eip2mqtt::adapters::mqtt
