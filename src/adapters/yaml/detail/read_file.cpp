#include "adapters/yaml/detail/read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "eip2mqtt/adapters/yaml/load_config.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

/// What a file that is not a regular one is, for a message: "a directory".
std::string_view kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "of an unknown kind";
}

}  // namespace

core::Result<std::string, std::string> read_file(const std::string& path, const std::string& what) {
    const auto cannot = [&](int error) {
        return core::fail("cannot read " + what + ": " + std::strerror(error));
    };
    const auto too_big = [&](const std::string& size) {
        return core::fail(what + " is " + size + " bytes; the limit is " +
                          std::to_string(max_file_bytes) + " (" +
                          std::to_string(max_file_bytes >> 20) + " MiB)");
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return cannot(errno);
    const struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat status = {};
    if (::fstat(fd, &status) != 0) return cannot(errno);
    if (!S_ISREG(status.st_mode)) {
        return core::fail(what + " is not a regular file (" + std::string(kind_of(status.st_mode)) +
                          ")");
    }
    if (static_cast<std::uintmax_t>(status.st_size) > max_file_bytes) {
        return too_big(std::to_string(status.st_size));
    }
    // Sized for one read, not copied through a stream (a plant's file is megabytes), and one
    // byte more, to see the end without growing.
    std::string text(static_cast<std::size_t>(status.st_size) + 1, '\0');
    std::size_t filled = 0;
    while (true) {
        if (filled == text.size()) {
            if (filled > max_file_bytes) {
                return too_big("more than " + std::to_string(max_file_bytes));
            }
            text.resize(std::min(std::max<std::size_t>(2 * filled, 4096), max_file_bytes + 1));
        }
        const auto n = ::read(fd, text.data() + filled, text.size() - filled);
        if (n < 0) {
            if (errno == EINTR) continue;
            return cannot(errno);
        }
        if (n == 0) break;
        filled += static_cast<std::size_t>(n);
    }
    text.resize(filled);
    return text;
}

}  // namespace eip2mqtt::adapters::yaml::detail
