#include "eip2mqtt/adapters/state/image_file.hpp"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <string_view>
#include <utility>

#include "adapters/state/detail/image_format.hpp"
#include "eip2mqtt/adapters/state/atomic_file.hpp"

namespace eip2mqtt::adapters::state {
namespace {

/// "what: the system's reason".
std::string io_failure(std::string what, int error) {
    what += ": ";
    what += std::strerror(error);
    return what;
}

std::string io_failure(std::string_view step, const std::string& file, int error) {
    std::string what(step);  // appended, not `+`: GCC 12 warns on the latter (-Wrestrict)
    what += ' ';
    what += file;
    return io_failure(std::move(what), error);
}

/// Reads up to `limit` + 1 bytes from the start of `fd`, so that an oversized file shows as
/// such; nullopt (errno set) on failure.
std::optional<std::vector<std::byte>> read_head(int fd, std::size_t limit) {
    std::vector<std::byte> bytes(limit + 1);
    std::size_t size = 0;
    while (size < bytes.size()) {
        const auto n =
            ::pread(fd, bytes.data() + size, bytes.size() - size, static_cast<off_t>(size));
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return std::nullopt;
        if (n == 0) break;
        size += static_cast<std::size_t>(n);
    }
    bytes.resize(size);
    return bytes;
}

bool write_at(int fd, std::span<const std::byte> data, off_t offset) {
    while (!data.empty()) {
        const auto n = ::pwrite(fd, data.data(), data.size(), offset);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        data = data.subspan(static_cast<std::size_t>(n));
        offset += n;
    }
    return true;
}

/// The newest slot that checks out, with its index; else why none does.
core::Result<std::pair<detail::StoredImage, std::size_t>, std::string> newest_slot(
    std::span<const std::byte> file) {
    std::optional<std::pair<detail::StoredImage, std::size_t>> newest;
    std::string why = "truncated";
    for (std::size_t i = 0; i < detail::slot_count; ++i) {
        if (file.size() < (i + 1) * detail::slot_size) break;
        auto slot = detail::decode_slot(file.subspan(i * detail::slot_size, detail::slot_size));
        if (!slot) {
            if (i == 0) why = slot.error();
            continue;
        }
        if (!newest || slot->sequence > newest->first.sequence) newest.emplace(*slot, i);
    }
    if (!newest) return core::fail("no valid slot (" + why + ")");
    return *newest;
}

/// What a file holds: its newest image (of whatever layout), the slot it is in, and whether
/// saves may overwrite the file in place; else why it holds none.
struct Found {
    detail::StoredImage image;
    std::size_t slot = 0;
    bool in_place = false;
};

core::Result<Found, std::string> decode_file(std::span<const std::byte> bytes) {
    const auto format = detail::format_of(bytes);
    if (format == detail::format_slotted) {
        auto newest = newest_slot(bytes);
        if (!newest) return core::fail(newest.error());
        return Found{std::move(newest->first), newest->second,
                     bytes.size() == detail::slotted_file_size};
    }
    if (format == detail::format_whole) {
        auto whole = detail::decode_whole(bytes);
        if (!whole) return core::fail(whole.error());
        return Found{std::move(*whole), 0, false};  // rewritten with slots by the first save
    }
    if (format)
        return core::fail("format version " + std::to_string(*format) + ", expected 2 or 1");
    return core::fail(std::string("not an eip2mqtt image (bad magic or truncated)"));
}

}  // namespace

ImageFile::ImageFile(std::string path, std::string exchange, std::uint64_t fingerprint,
                     std::size_t length)
    : path_(std::move(path)),
      exchange_(std::move(exchange)),
      fingerprint_(fingerprint),
      length_(length) {
    read_existing();
}

ImageFile::~ImageFile() { close_file(); }

void ImageFile::close_file() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

void ImageFile::read_existing() {
    const auto ignored = [&](std::string_view why) {
        spdlog::warn("exchange {}: ignoring saved image {}: {}; initial values apply", exchange_,
                     path_, why);
    };
    // O_NONBLOCK: a FIFO put in its place must not hang the start; regular files ignore it.
    int fd = ::open(path_.c_str(), O_RDWR | O_CLOEXEC | O_NONBLOCK);
    const bool writable = fd >= 0;
    if (fd < 0 && (errno == EACCES || errno == EROFS)) {
        fd = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    }
    if (fd < 0) {
        if (errno != ENOENT) return ignored(io_failure("open", path_, errno));
        spdlog::info("exchange {}: no saved image in {}; initial values apply", exchange_, path_);
        return;
    }
    struct stat st {};
    std::optional<std::vector<std::byte>> bytes;
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ignored("not a regular file");
    } else if (bytes = read_head(fd, detail::slotted_file_size); !bytes) {
        ignored(io_failure("read", path_, errno));
    }
    core::Result<Found, std::string> found = core::fail(std::string());
    if (bytes) {
        found = decode_file(*bytes);
        if (!found) ignored(found.error());
    }
    if (found &&
        (found->image.fingerprint != fingerprint_ || found->image.data.size() != length_)) {
        // An expected outcome of a configuration change, not a fault.
        spdlog::info(
            "exchange {}: saved image {} was written for another layout (length, tag addresses "
            "or types changed); initial values apply",
            exchange_, path_);
        found = core::fail(std::string());
    }
    if (!found) {
        ::close(fd);
        return;
    }
    sequence_ = found->image.sequence;
    newest_ = found->slot;
    loaded_ = std::move(found->image.data);
    in_place_ = writable && found->in_place;
    if (in_place_) {
        fd_ = fd;
    } else {
        ::close(fd);
    }
}

std::optional<std::string> ImageFile::save(std::span<const std::byte> data) {
    if (data.size() > detail::max_slot_data) return "image of " + exchange_ + " too large";
    return fd_ >= 0 ? save_in_place(data) : create(data);
}

std::optional<std::string> ImageFile::save_in_place(std::span<const std::byte> data) {
    const std::size_t slot = 1 - newest_;
    std::array<std::byte, detail::slot_size> bytes{};
    detail::encode_slot(sequence_ + 1, fingerprint_, data, bytes);
    if (!write_at(fd_, bytes, static_cast<off_t>(slot * detail::slot_size))) {
        return io_failure("write", path_, errno);
    }
    if (::fdatasync(fd_) != 0) return io_failure("fdatasync", path_, errno);
    struct stat st {};
    if (::fstat(fd_, &st) == 0 && st.st_nlink == 0) {
        // Removed while open (a state directory cleaned by hand): this save reached no file a
        // restart would read.
        spdlog::warn("exchange {}: saved image {} was removed; writing it again", exchange_, path_);
        close_file();
        return create(data);
    }
    ++sequence_;
    newest_ = slot;
    return std::nullopt;
}

std::optional<std::string> ImageFile::create(std::span<const std::byte> data) {
    // Both slots' blocks are written now, so that later saves overwrite them in place.
    std::vector<std::byte> bytes(detail::slotted_file_size);
    detail::encode_slot(sequence_ + 1, fingerprint_, data,
                        std::span(bytes).first(detail::slot_size));
    const std::span<const std::byte> parts[] = {bytes};
    if (const auto failed = write_file_atomically(path_, parts, 0644)) {
        return io_failure(failed->step, failed->error);
    }
    ++sequence_;
    newest_ = 0;
    // Should it fail, the image is saved all the same, and the next save creates the file again.
    fd_ = ::open(path_.c_str(), O_RDWR | O_CLOEXEC);
    return std::nullopt;
}

}  // namespace eip2mqtt::adapters::state
