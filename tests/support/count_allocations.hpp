#pragma once
/// Counts the heap allocations (operator new) that the calling thread makes while `f` runs, to
/// show that a warm data path allocates nothing. Using it links count_allocations.cpp,
/// which replaces the test program's global operator new; it counts only while asked, and only
/// on the asking thread (Paho's threads, say, are not counted).

#include <cstddef>
#include <functional>

namespace eip2mqtt::test {

std::size_t allocations_during(const std::function<void()>& f);

}  // namespace eip2mqtt::test
