#pragma once
/// Replaces a file so that a crash or a power cut leaves either the old file or the new one,
/// never a mix: the new content goes to a temporary beside it, is fsynced, renamed over the old
/// file, and the directory is fsynced. Used for produced images.

#include <sys/types.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>

namespace eip2mqtt::adapters::state {

struct AtomicWriteFailure {
    std::string step;       ///< what failed, with the file it failed on ("open x.tmp")
    int error = 0;          ///< its errno
    bool replaced = false;  ///< the new file is in place: only the directory's fsync failed
};

/// Writes `parts`, end to end, as the new content of `path` (created with `mode`). nullopt on
/// success; on failure the temporary is removed and, unless `replaced`, the old file is intact.
std::optional<AtomicWriteFailure> write_file_atomically(
    const std::string& path, std::span<const std::span<const std::byte>> parts, mode_t mode);

}  // namespace eip2mqtt::adapters::state
