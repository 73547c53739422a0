#pragma once
/// A real tmpfs the test mounts on a fresh directory and unmounts at the end: a file system to
/// fill up or to mount read-only, for what the gateway does with a full or read-only
/// state directory. Mounting needs CAP_SYS_ADMIN (the suite runs as root); without it,
/// mounted() is false and the test skips with error().

#include <cstddef>
#include <string>

namespace eip2mqtt::test {

class Tmpfs {
public:
    /// `size_bytes` of room (rounded up to pages by the kernel); read-only when `read_only`.
    /// Mounted on `at` when given (created when missing; a gateway's state_dir), else on a
    /// fresh directory under /tmp.
    explicit Tmpfs(std::size_t size_bytes, bool read_only = false, std::string at = {});
    /// Unmounts (lazily, should a process still hold a file there) and removes the directory
    /// it made.
    ~Tmpfs();
    Tmpfs(const Tmpfs&) = delete;
    Tmpfs& operator=(const Tmpfs&) = delete;

    bool mounted() const { return mounted_; }
    const std::string& error() const { return error_; }
    const std::string& path() const { return path_; }

    /// Writes `name` in the tmpfs until the file system refuses with ENOSPC, the last partial
    /// page byte by byte: the disk is full. The bytes written.
    std::size_t fill(const std::string& name = "filler") const;
    /// Bytes free on it now.
    std::size_t free_bytes() const;
    /// Removes `name`: the room it took is free again.
    void release(const std::string& name = "filler") const;

private:
    std::string path_;
    bool made_ = false;  ///< path_ is a directory of its own, removed at the end
    bool mounted_ = false;
    std::string error_;
};

}  // namespace eip2mqtt::test
