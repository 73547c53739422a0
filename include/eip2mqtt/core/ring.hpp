#pragma once
/// A FIFO in one circular buffer that grows by doubling and never shrinks until release().
/// std::deque allocates a block at its back and frees one at its front every few elements as
/// it moves (512 bytes a block in libstdc++: three MQTT messages, 64 arrival times): on the
/// data path, that was a malloc and a free every few datagrams or publications. A Ring
/// allocates only when it grows past its largest size so far (#6).
///
/// Elements are moved when the ring grows, so views into them (a std::string's inline buffer)
/// must be taken again after a push_back that returned true.
///
/// Not thread-safe.

#include <cstddef>
#include <utility>
#include <vector>

namespace eip2mqtt::core {

template <class T>
class Ring {
public:
    bool empty() const { return count_ == 0; }
    std::size_t size() const { return count_; }
    std::size_t capacity() const { return slots_.size(); }

    /// Element `i` from the front (i < size()).
    T& operator[](std::size_t i) { return slots_[(head_ + i) & (slots_.size() - 1)]; }
    const T& operator[](std::size_t i) const { return slots_[(head_ + i) & (slots_.size() - 1)]; }
    T& front() { return (*this)[0]; }
    T& back() { return (*this)[count_ - 1]; }

    /// Appends `item`; true when the ring grew, which moved every element.
    bool push_back(T item) {
        const bool grew = count_ == slots_.size();
        if (grew) grow();
        (*this)[count_] = std::move(item);
        ++count_;
        return grew;
    }

    /// Removes the front element, leaving a default T in its slot (so that it holds nothing).
    void pop_front() {
        slots_[head_] = T{};
        head_ = (head_ + 1) & (slots_.size() - 1);
        --count_;
    }

    /// Removes every element; keeps the buffer.
    void clear() {
        while (!empty()) pop_front();
        head_ = 0;
    }

    /// Frees the buffer (after a backlog, whose peak it kept); only when empty.
    void release() {
        if (count_ != 0) return;
        std::vector<T>().swap(slots_);
        head_ = 0;
    }

private:
    void grow() {
        // A power of two, so that an index wraps with a mask.
        std::vector<T> bigger(slots_.empty() ? 16 : 2 * slots_.size());
        for (std::size_t i = 0; i < count_; ++i) bigger[i] = std::move((*this)[i]);
        slots_.swap(bigger);
        head_ = 0;
    }

    std::vector<T> slots_;
    std::size_t head_ = 0;
    std::size_t count_ = 0;
};

}  // namespace eip2mqtt::core
