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

}  // namespace eip2mqtt::app::detail
