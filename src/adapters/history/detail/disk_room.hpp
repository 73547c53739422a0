#pragma once
// How the journal shares its room on disk, and the reserve that lets it make room on a full
// disk. In WAL mode every change, a DELETE included, is first written to the WAL, and a
// checkpoint may have to extend the database file: a journal that filled the disk could not
// even delete its oldest entries. So the journal holds a reserve, a file of allocated blocks
// beside it, and gives it up only to make room (see Journal::recover_from_full).

#include <cstdint>
#include <string>

namespace eip2mqtt::adapters::history::detail {

/// What each part of the journal may take on disk; the parts add up to `limit`.
struct SpacePlan {
    std::uint64_t limit = 0;     ///< max_bytes, or less when the filesystem has less room
    std::uint64_t wal = 0;       ///< the WAL is checkpointed past this
    std::uint64_t wal_slot = 0;  ///< and never larger: one transaction more
    std::uint64_t chunk = 0;     ///< one transaction's entries at most (bytes of payload)
    std::uint64_t reserve = 0;   ///< the reserve file: a checkpoint of a full WAL and a DELETE
    std::uint64_t database = 0;  ///< the database file
};

/// The plan for a journal allowed `max_bytes` on a filesystem where it may have `room` (its own
/// files, plus what is free, less a share left to the other files of the state directory).
/// Sizes are whole pages of `page_size`.
SpacePlan plan_space(std::uint64_t max_bytes, std::uint64_t room, std::uint64_t page_size);

/// Bytes a journal whose files take `own_bytes` may have on the filesystem of `directory`:
/// its own, plus what is free there, less a thirty-second of the filesystem (4 MiB at most)
/// left for the other files of the state directory. Unknown (statvfs failed): `fallback`.
std::uint64_t room_on_disk(const std::string& directory, std::uint64_t own_bytes,
                           std::uint64_t fallback);

/// The size of `path` (0 when absent), without following a symbolic link.
std::uint64_t file_bytes(const std::string& path);

/// A file of allocated blocks (not a sparse one) that the journal gives back to the filesystem
/// when it is full. Never follows a symbolic link: one at its path is removed, not written to.
class Reserve {
public:
    explicit Reserve(std::string path);
    ~Reserve();
    Reserve(const Reserve&) = delete;
    Reserve& operator=(const Reserve&) = delete;

    /// Allocates `bytes` (shrinks to them when larger); false when the disk has not the room,
    /// and then holds what it held before.
    bool hold(std::uint64_t bytes);
    /// Gives every block back to the filesystem.
    void release();
    std::uint64_t held() const { return held_; }
    const std::string& path() const { return path_; }

private:
    bool open();

    std::string path_;
    int fd_ = -1;
    std::uint64_t held_ = 0;
};

}  // namespace eip2mqtt::adapters::history::detail
