#include "tests/support/count_allocations.hpp"

#include <cstdlib>
#include <new>

namespace {

thread_local bool counting = false;
thread_local std::size_t allocations = 0;

}  // namespace

namespace eip2mqtt::test {

std::size_t allocations_during(const std::function<void()>& f) {
    allocations = 0;
    counting = true;
    f();
    counting = false;
    return allocations;
}

}  // namespace eip2mqtt::test

// The replaceable global allocation functions ([new.delete.single]); the array and aligned
// forms' defaults call these or malloc's family, so every new is counted and freed alike.
void* operator new(std::size_t size) {
    if (counting) ++allocations;
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}

void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
