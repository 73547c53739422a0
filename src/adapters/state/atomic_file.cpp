#include "eip2mqtt/adapters/state/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string_view>
#include <utility>

namespace eip2mqtt::adapters::state {
namespace {

/// Writes all of `data`, retrying partial writes and EINTR.
bool write_all(int fd, const std::byte* data, std::size_t size) {
    while (size > 0) {
        const auto n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

AtomicWriteFailure failure(std::string_view step, const std::string& file, int error,
                           bool replaced = false) {
    std::string what(step);  // appended, not `+`: GCC 12 warns on the latter (-Wrestrict)
    what += ' ';
    what += file;
    return {std::move(what), error, replaced};
}

}  // namespace

std::optional<AtomicWriteFailure> write_file_atomically(
    const std::string& path, std::span<const std::span<const std::byte>> parts, mode_t mode) {
    const std::string temporary = path + ".tmp";
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
    if (fd < 0) return failure("open", temporary, errno);
    bool written = true;
    for (const auto part : parts) {
        if (!write_all(fd, part.data(), part.size())) {
            written = false;
            break;
        }
    }
    if (!written || ::fsync(fd) != 0) {
        const int error = errno;
        ::close(fd);
        ::unlink(temporary.c_str());
        return failure("write", temporary, error);
    }
    if (::close(fd) != 0) {
        const int error = errno;
        ::unlink(temporary.c_str());
        return failure("close", temporary, error);
    }
    if (::rename(temporary.c_str(), path.c_str()) != 0) {
        const int error = errno;
        ::unlink(temporary.c_str());
        return failure("rename", temporary, error);
    }
    // The new file is in place now; only the rename's durability across a power cut is left.
    const auto parent = std::filesystem::path(path).parent_path();
    const std::string directory = parent.empty() ? std::string(".") : parent.string();
    const int dir = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dir < 0 || ::fsync(dir) != 0) {
        const int error = errno;
        if (dir >= 0) ::close(dir);
        return failure("fsync directory", directory, error, true);
    }
    ::close(dir);
    return std::nullopt;
}

}  // namespace eip2mqtt::adapters::state
