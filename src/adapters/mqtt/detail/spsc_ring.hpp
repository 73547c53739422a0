#pragma once
/// A bounded FIFO between one producer thread and one consumer, without locks: how the loop
/// hands publications to the MQTT sender (and gets spare buffers back) without taking a lock
/// per publication (#6). Either side may be played by several threads in turn if they exclude
/// each other (a mutex orders them), never by two at once.
///
/// Module-private (src/adapters/mqtt/detail).

#include <atomic>
#include <cstddef>
#include <memory>
#include <utility>

namespace eip2mqtt::adapters::mqtt::detail {

template <class T, std::size_t Capacity>
class SpscRing {
    static_assert(Capacity > 0 && (Capacity & (Capacity - 1)) == 0, "a power of two");

public:
    SpscRing() : slots_(std::make_unique<T[]>(Capacity)) {}

    /// Producer: moves `item` in; false, and `item` untouched, when full.
    bool try_push(T& item) {
        const std::size_t tail = tail_.load(std::memory_order_relaxed);
        if (tail - head_.load(std::memory_order_acquire) == Capacity) return false;
        slots_[tail & (Capacity - 1)] = std::move(item);
        tail_.store(tail + 1, std::memory_order_release);
        return true;
    }

    /// Consumer: moves the oldest item into `out`; false when empty.
    bool try_pop(T& out) {
        const std::size_t head = head_.load(std::memory_order_relaxed);
        if (head == tail_.load(std::memory_order_acquire)) return false;
        out = std::move(slots_[head & (Capacity - 1)]);
        head_.store(head + 1, std::memory_order_release);
        return true;
    }

    /// Exact on the consumer's side; from the producer's, it may miss what was just taken.
    bool empty() const {
        return head_.load(std::memory_order_acquire) == tail_.load(std::memory_order_acquire);
    }
    std::size_t size() const {
        const std::size_t head = head_.load(std::memory_order_acquire);  // first: never past tail
        return tail_.load(std::memory_order_acquire) - head;
    }

private:
    std::unique_ptr<T[]> slots_;
    alignas(64) std::atomic<std::size_t> head_{0};  ///< next to pop (the consumer's)
    alignas(64) std::atomic<std::size_t> tail_{0};  ///< next to push (the producer's)
};

}  // namespace eip2mqtt::adapters::mqtt::detail
