#pragma once
// The gateway's heap policy: glibc's thresholds held fixed from the start of `run`, and, after a
// configuration is loaded and its plans are built (start and reload), the heap that parsing
// used handed back to the system.

namespace eip2mqtt::app::detail {

/// Returns free heap pages to the system (glibc's malloc_trim; a no-op elsewhere). glibc keeps
/// freed memory for reuse: without this, the resident size stays at the loader's peak.
void release_heap();

/// Holds glibc's mmap and trim thresholds at their defaults for the rest of the process (a
/// no-op elsewhere). Called before the configuration is read.
void keep_heap_thresholds();

}  // namespace eip2mqtt::app::detail
