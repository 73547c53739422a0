#include "adapters/history/detail/disk_room.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace eip2mqtt::adapters::history::detail {
namespace {

std::uint64_t whole_pages(std::uint64_t bytes, std::uint64_t page) { return bytes / page * page; }

}  // namespace

SpacePlan plan_space(std::uint64_t max_bytes, std::uint64_t room, std::uint64_t page_size) {
    SpacePlan plan;
    plan.limit = std::min(max_bytes, room);
    // A sixteenth for the WAL (checkpointed when full), at least 8 pages, at most 8 MiB: the
    // checkpoint's fsync then comes every 8 MiB at most, and the reserve stays small.
    plan.wal = whole_pages(std::clamp<std::uint64_t>(plan.limit / 16, 8 * page_size, 8ull << 20),
                           page_size);
    // A transaction's pages in the WAL come to about twice its payload (the B-tree's pages are
    // part full, and its parents and pointer-map pages change with it): one chunk's transaction
    // past the checkpoint size fits in half a WAL more.
    plan.chunk = std::max(page_size, whole_pages(plan.wal / 8, page_size));
    plan.wal_slot = plan.wal + plan.wal / 2;
    // A checkpoint of a full WAL may extend the database by as much; then the DELETE of the
    // oldest entries and the moves of pages that give their room back, a chunk each.
    plan.reserve = plan.wal_slot + 2 * plan.chunk;
    const auto others = plan.wal_slot + plan.reserve;
    plan.database = plan.limit > others + 8 * page_size
                        ? whole_pages(plan.limit - others, page_size)
                        : 8 * page_size;
    return plan;
}

std::uint64_t room_on_disk(const std::string& directory, std::uint64_t own_bytes,
                           std::uint64_t fallback) {
    struct statvfs fs {};
    if (::statvfs(directory.c_str(), &fs) != 0) return fallback;
    const auto free = static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize;
    const auto total = static_cast<std::uint64_t>(fs.f_blocks) * fs.f_frsize;
    const auto others = std::min<std::uint64_t>(total / 32, 4ull << 20);
    const auto room = own_bytes + free;
    return room > others ? room - others : 0;
}

std::uint64_t file_bytes(const std::string& path) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return 0;
    return static_cast<std::uint64_t>(st.st_size);
}

Reserve::Reserve(std::string path) : path_(std::move(path)) {}

Reserve::~Reserve() {
    if (fd_ >= 0) ::close(fd_);
}

bool Reserve::open() {
    if (fd_ >= 0) return true;
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd_ < 0 && errno == ELOOP) {
        // A symbolic link where the reserve goes: never ours, and never followed.
        ::unlink(path_.c_str());
        fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0600);
    }
    if (fd_ < 0) return false;
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd_);
        fd_ = -1;
        return false;
    }
    held_ = std::min(static_cast<std::uint64_t>(st.st_size),
                     static_cast<std::uint64_t>(st.st_blocks) * 512);
    return true;
}

bool Reserve::hold(std::uint64_t bytes) {
    if (!open()) return false;
    if (bytes <= held_) {
        if (bytes < held_ && ::ftruncate(fd_, static_cast<off_t>(bytes)) == 0) held_ = bytes;
        return true;
    }
    if (::posix_fallocate(fd_, 0, static_cast<off_t>(bytes)) == 0) {
        held_ = bytes;
        return true;
    }
    // A filesystem may keep part of a failed allocation: back to what was held.
    if (::ftruncate(fd_, static_cast<off_t>(held_)) != 0) held_ = 0;
    return false;
}

void Reserve::release() {
    if (!open()) return;
    if (::ftruncate(fd_, 0) == 0) held_ = 0;
}

}  // namespace eip2mqtt::adapters::history::detail
