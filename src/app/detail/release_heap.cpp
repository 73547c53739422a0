#include "app/detail/release_heap.hpp"

// __GLIBC__ comes from the C library's own headers: test it only after including one.
#if __has_include(<malloc.h>)
#include <malloc.h>
#endif

namespace eip2mqtt::app::detail {

void release_heap() {
#if defined(__GLIBC__)
    ::malloc_trim(0);
#endif
}

void keep_heap_thresholds() {
#if defined(__GLIBC__)
    // Left dynamic, glibc raises both thresholds to the largest mapped block freed so far: the
    // megabytes of a configuration file read at start-up lift them to tens of MB for good. A
    // thread's arena then keeps its free top resident, which malloc_trim does not give back
    // (it trims only the main arena's top): the MQTT sender's kept 1-2 MB. Setting them turns
    // the adjustment off (docs/decisions/0006).
    constexpr int kDefaultThreshold = 128 * 1024;
    ::mallopt(M_MMAP_THRESHOLD, kDefaultThreshold);
    ::mallopt(M_TRIM_THRESHOLD, kDefaultThreshold);
#endif
}

}  // namespace eip2mqtt::app::detail
