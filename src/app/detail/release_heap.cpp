#include "app/detail/release_heap.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace eip2mqtt::app::detail {

void release_heap() {
#if defined(__GLIBC__)
    ::malloc_trim(0);
#endif
}

}  // namespace eip2mqtt::app::detail
