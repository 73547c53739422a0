#pragma once
/// An immutable value shared by a count of its holders, in one pointer where std::shared_ptr
/// takes two: a Value that may hold a text or an array stays 16 bytes, and a ReportFilter (one
/// per consumed tag) 32.

#include <atomic>
#include <cstdint>
#include <utility>

namespace eip2mqtt::core::plan {

template <class T>
class Shared {
public:
    Shared() = default;  ///< null: only a moved-from or default Value holds one
    explicit Shared(T value) : block_(new Block{std::move(value), {1}}) {}
    Shared(const Shared& other) noexcept : block_(other.block_) {
        // Relaxed: a new holder needs no order, as with std::shared_ptr.
        if (block_ != nullptr) block_->holders.fetch_add(1, std::memory_order_relaxed);
    }
    Shared(Shared&& other) noexcept : block_(std::exchange(other.block_, nullptr)) {}
    Shared& operator=(Shared other) noexcept {
        std::swap(block_, other.block_);
        return *this;
    }
    ~Shared() {
        if (block_ != nullptr && block_->holders.fetch_sub(1, std::memory_order_acq_rel) == 1) {
            delete block_;
        }
    }

    /// Equal contents (a configuration's `initial` compares so on reload), or both null.
    friend bool operator==(const Shared& a, const Shared& b) {
        if (a.block_ == b.block_) return true;
        return a.block_ != nullptr && b.block_ != nullptr && a.block_->value == b.block_->value;
    }

    const T& operator*() const { return block_->value; }
    const T* operator->() const { return &block_->value; }

private:
    struct Block {
        T value;
        std::atomic<std::uint32_t> holders;
    };
    Block* block_ = nullptr;
};

}  // namespace eip2mqtt::core::plan
