#pragma once
/// OutOfLine<T>: a copyable value of T kept on the heap, or not at all while it was never
/// written, so that a member rarely set costs one pointer in a type held 100,000 times (the
/// settings of a tag that few tags use: docs/decisions/0001-configurations-of-100000-tags.md).
/// Copies copy the T, and equality compares contents: an OutOfLine never written equals one holding
/// a default T.
///
/// Threading: as T; the shared default is immutable.

#include <memory>

namespace eip2mqtt::core {

template <class T>
class OutOfLine {
public:
    OutOfLine() = default;
    OutOfLine(const OutOfLine& other) : value_(copy(other)) {}
    OutOfLine(OutOfLine&&) noexcept = default;
    OutOfLine& operator=(const OutOfLine& other) {
        if (this != &other) value_ = copy(other);
        return *this;
    }
    OutOfLine& operator=(OutOfLine&&) noexcept = default;
    ~OutOfLine() = default;

    /// The value; a shared default T while none was written (or after a move from this).
    const T& get() const { return value_ ? *value_ : default_value(); }

    /// The value to write, allocated (as a default T) on first use.
    T& mutable_get() {
        if (!value_) value_ = std::make_unique<T>();
        return *value_;
    }

    /// True once mutable_get() allocated the value, whatever it holds.
    bool allocated() const { return value_ != nullptr; }

    friend bool operator==(const OutOfLine& a, const OutOfLine& b) { return a.get() == b.get(); }

private:
    static std::unique_ptr<T> copy(const OutOfLine& other) {
        return other.value_ ? std::make_unique<T>(*other.value_) : nullptr;
    }
    static const T& default_value() {
        static const T value{};
        return value;
    }

    std::unique_ptr<T> value_;
};

}  // namespace eip2mqtt::core
