#pragma once
// Shared by the gateway's start and reload: after a configuration is loaded and its plans are
// built, hand the heap that parsing used back to the system.

namespace eip2mqtt::app::detail {

/// Returns free heap pages to the system (glibc's malloc_trim; a no-op elsewhere). glibc keeps
/// freed memory for reuse: without this, the resident size stays at the loader's peak.
void release_heap();

}  // namespace eip2mqtt::app::detail
