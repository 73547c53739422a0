#pragma once
/// A small expected-like type for the core: GCC 12 in C++20 has no std::expected, and the core
/// returns errors as values because bad input is routine there.

#include <cassert>
#include <utility>
#include <variant>

namespace eip2mqtt::core {

/// Wraps an error so that Result<T, E> can be built from it even when T and E convert.
template <class E>
struct Failure {
    E error;
};

template <class E>
Failure<std::decay_t<E>> fail(E&& error) {
    return {std::forward<E>(error)};
}

/// Either a value of T or an error of E.
template <class T, class E>
class Result {
public:
    Result(T value) : storage_(std::in_place_index<0>, std::move(value)) {}
    template <class F>
    Result(Failure<F> failure) : storage_(std::in_place_index<1>, E(std::move(failure.error))) {}

    bool ok() const { return storage_.index() == 0; }
    explicit operator bool() const { return ok(); }

    T& value() & {
        assert(ok());
        return std::get<0>(storage_);
    }
    const T& value() const& {
        assert(ok());
        return std::get<0>(storage_);
    }
    T&& value() && {
        assert(ok());
        return std::get<0>(std::move(storage_));
    }
    const E& error() const {
        assert(!ok());
        return std::get<1>(storage_);
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

private:
    std::variant<T, E> storage_;
};

}  // namespace eip2mqtt::core
