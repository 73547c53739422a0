#pragma once
/// A FIFO in one circular buffer that grows by doubling and never shrinks until release().
/// std::deque allocates a block at its back and frees one at its front every few elements as
/// it moves (512 bytes a block in libstdc++: three MQTT messages, 64 arrival times): on the
/// data path, that was a malloc and a free every few datagrams or publications. A Ring
/// allocates only when it grows past its largest size so far.
///
/// Elements are moved when the ring grows, so views into them (a std::string's inline buffer)
/// must be taken again after a push_back that returned true.
///
/// Not thread-safe.

#include <cstddef>
#include <memory>
#include <utility>

namespace eip2mqtt::core {

template <class T>
class Ring {
public:
    Ring() = default;
    Ring(const Ring& other) : Ring() {
        if (other.capacity_ == 0) return;
        slots_ = std::allocator<T>().allocate(other.capacity_);
        capacity_ = other.capacity_;
        for (; count_ < other.count_; ++count_) std::construct_at(slots_ + count_, other[count_]);
    }
    Ring(Ring&& other) noexcept
        : slots_(std::exchange(other.slots_, nullptr)),
          capacity_(std::exchange(other.capacity_, 0)),
          head_(std::exchange(other.head_, 0)),
          count_(std::exchange(other.count_, 0)) {}
    Ring& operator=(Ring other) noexcept {
        std::swap(slots_, other.slots_);
        std::swap(capacity_, other.capacity_);
        std::swap(head_, other.head_);
        std::swap(count_, other.count_);
        return *this;
    }
    ~Ring() {
        clear();
        deallocate();
    }

    bool empty() const { return count_ == 0; }
    std::size_t size() const { return count_; }
    std::size_t capacity() const { return capacity_; }

    /// Element `i` from the front (i < size()).
    T& operator[](std::size_t i) { return slots_[(head_ + i) & (capacity_ - 1)]; }
    const T& operator[](std::size_t i) const { return slots_[(head_ + i) & (capacity_ - 1)]; }
    T& front() { return (*this)[0]; }
    T& back() { return (*this)[count_ - 1]; }

    /// Appends `item`; true when the ring grew, which moved every element.
    bool push_back(T item) {
        const bool grew = count_ == capacity_;
        if (grew) grow();
        std::construct_at(&(*this)[count_], std::move(item));
        ++count_;
        return grew;
    }

    /// Removes the front element.
    void pop_front() {
        std::destroy_at(&front());
        head_ = (head_ + 1) & (capacity_ - 1);
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
        deallocate();
        head_ = 0;
    }

private:
    void grow() {
        // A power of two, so that an index wraps with a mask. Slots are constructed only when
        // used: a large buffer's untouched pages cost no resident memory.
        const std::size_t bigger = capacity_ == 0 ? 16 : 2 * capacity_;
        T* moved = std::allocator<T>().allocate(bigger);
        for (std::size_t i = 0; i < count_; ++i) {
            std::construct_at(moved + i, std::move((*this)[i]));
            std::destroy_at(&(*this)[i]);
        }
        deallocate();
        slots_ = moved;
        capacity_ = bigger;
        head_ = 0;
    }

    void deallocate() {
        if (slots_ != nullptr) std::allocator<T>().deallocate(slots_, capacity_);
        slots_ = nullptr;
        capacity_ = 0;
    }

    T* slots_ = nullptr;  ///< capacity_ slots; count_ of them constructed, from head_ on
    std::size_t capacity_ = 0;
    std::size_t head_ = 0;
    std::size_t count_ = 0;
};

}  // namespace eip2mqtt::core
