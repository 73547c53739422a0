#pragma once
/// A real tmpfs of a given size, mounted on a directory the test makes, for tests of a full
/// disk: what fills it gets ENOSPC from the kernel, as on a real disk. Unmounted (lazily if it
/// is still busy) and its directory removed however the test ends. Mounting needs root: tests
/// skip without it (available()).

#include <cstdint>
#include <string>

namespace eip2mqtt::test {

class TmpfsMount {
public:
    /// Why a tmpfs cannot be mounted here (empty: it can).
    static std::string unavailable();

    /// Mounts a tmpfs of `bytes` on `directory` (an existing, empty one), or on a new one under
    /// /tmp when empty; throws when it cannot.
    explicit TmpfsMount(std::uint64_t bytes, const std::string& directory = "");
    ~TmpfsMount();
    TmpfsMount(const TmpfsMount&) = delete;
    TmpfsMount& operator=(const TmpfsMount&) = delete;

    const std::string& path() const { return path_; }
    /// Bytes free on it now.
    std::uint64_t free_bytes() const;
    /// Fills it up with a file (`name`) until the kernel refuses more: the disk is full.
    void fill(const std::string& name) const;

private:
    std::string path_;
    bool made_ = false;  ///< the directory is ours to remove
};

}  // namespace eip2mqtt::test
