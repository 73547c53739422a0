#include "tests/support/tmpfs_mount.hpp"

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace eip2mqtt::test {

std::string TmpfsMount::unavailable() {
    if (::geteuid() != 0) return "mounting a tmpfs needs root (the tests run as root in CI)";
    return {};
}

TmpfsMount::TmpfsMount(std::uint64_t bytes, const std::string& directory) : path_(directory) {
    if (path_.empty()) {
        char name[] = "/tmp/eip2mqtt-tmpfs-XXXXXX";
        if (::mkdtemp(name) == nullptr) throw std::runtime_error("mkdtemp failed");
        path_ = name;
        made_ = true;
    }
    const auto options = "size=" + std::to_string(bytes) + ",mode=0755";
    if (::mount("tmpfs", path_.c_str(), "tmpfs", MS_NOSUID | MS_NODEV, options.c_str()) != 0) {
        const std::string error = std::strerror(errno);
        if (made_) ::rmdir(path_.c_str());
        throw std::runtime_error("cannot mount a tmpfs on " + path_ + ": " + error);
    }
}

TmpfsMount::~TmpfsMount() {
    if (::umount2(path_.c_str(), 0) != 0) ::umount2(path_.c_str(), MNT_DETACH);
    if (made_) ::rmdir(path_.c_str());
}

std::uint64_t TmpfsMount::free_bytes() const {
    struct statvfs fs {};
    if (::statvfs(path_.c_str(), &fs) != 0) return 0;
    return static_cast<std::uint64_t>(fs.f_bavail) * fs.f_frsize;
}

void TmpfsMount::fill(const std::string& name) const {
    const auto file = path_ + "/" + name;
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
    if (fd < 0) throw std::runtime_error("cannot create " + file);
    const std::vector<char> block(4096, 'f');
    // Bounded: a tmpfs is no larger than its size option.
    for (int i = 0; i < (1 << 20); ++i) {
        if (::write(fd, block.data(), block.size()) <= 0) break;
    }
    // The last partial page too, byte by byte at most a page.
    for (int i = 0; i < 4096; ++i) {
        if (::write(fd, block.data(), 1) <= 0) break;
    }
    ::close(fd);
}

}  // namespace eip2mqtt::test
