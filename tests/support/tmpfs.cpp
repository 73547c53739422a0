#include "tests/support/tmpfs.hpp"

#include <fcntl.h>
#include <sys/mount.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>
#include <vector>

namespace eip2mqtt::test {

Tmpfs::Tmpfs(std::size_t size_bytes, bool read_only, std::string at) : path_(std::move(at)) {
    if (path_.empty()) {
        char name[] = "/tmp/eip2mqtt-tmpfs-XXXXXX";
        if (::mkdtemp(name) == nullptr) throw std::runtime_error("mkdtemp failed");
        path_ = name;
        made_ = true;
    } else {
        std::filesystem::create_directories(path_);
    }
    const auto options = "size=" + std::to_string(size_bytes) + ",mode=0755";
    const unsigned long flags = read_only ? MS_RDONLY : 0;
    if (::mount("tmpfs", path_.c_str(), "tmpfs", flags, options.c_str()) != 0) {
        error_ = "cannot mount a tmpfs on " + path_ + ": " + std::strerror(errno) +
                 " (needs CAP_SYS_ADMIN)";
        return;
    }
    mounted_ = true;
}

Tmpfs::~Tmpfs() {
    if (mounted_) ::umount2(path_.c_str(), MNT_DETACH);
    if (made_) ::rmdir(path_.c_str());
}

std::size_t Tmpfs::fill(const std::string& name) const {
    const auto file = path_ + "/" + name;
    const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd < 0) return 0;
    const std::vector<char> chunk(4096, 'f');
    std::size_t written = 0;
    // Bounded by the file system's size; the count bounds it whatever happens.
    for (int i = 0; i < 1 << 20; ++i) {
        const auto n = ::write(fd, chunk.data(), chunk.size());
        if (n <= 0) break;
        written += static_cast<std::size_t>(n);
    }
    for (int i = 0; i < 4096; ++i) {
        if (::write(fd, chunk.data(), 1) <= 0) break;
        ++written;
    }
    ::close(fd);
    return written;
}

std::size_t Tmpfs::free_bytes() const {
    struct statvfs fs {};
    if (::statvfs(path_.c_str(), &fs) != 0) return 0;
    return static_cast<std::size_t>(fs.f_bavail) * fs.f_frsize;
}

void Tmpfs::release(const std::string& name) const { std::filesystem::remove(path_ + "/" + name); }

}  // namespace eip2mqtt::test
