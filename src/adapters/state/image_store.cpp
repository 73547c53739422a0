#include "eip2mqtt/adapters/state/image_store.hpp"

#include <fcntl.h>
#include <spdlog/spdlog.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <string_view>
#include <utility>

#include "eip2mqtt/adapters/state/atomic_file.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::adapters::state {
namespace {

// File format, every integer little-endian:
//   magic "EIP2MQTT-IMG" (12) | format version u32 | layout fingerprint u64 |
//   data length u32 | FNV-1a 64 of the data u64 | data bytes
constexpr std::string_view magic = "EIP2MQTT-IMG";
constexpr std::uint32_t format_version = 1;
constexpr std::size_t header_size = 12 + 4 + 8 + 4 + 8;
// No image is larger than a datagram's data (1400 bytes); anything much bigger is not ours.
constexpr std::size_t max_file_size = header_size + 65536;

constexpr std::uint64_t fnv_offset = 0xcbf29ce484222325ULL;
constexpr std::uint64_t fnv_prime = 0x100000001b3ULL;

void fnv_add(std::uint64_t& hash, std::uint8_t byte) {
    hash ^= byte;
    hash *= fnv_prime;
}

std::uint64_t fnv1a(std::span<const std::byte> data) {
    std::uint64_t hash = fnv_offset;
    for (const auto b : data) fnv_add(hash, static_cast<std::uint8_t>(b));
    return hash;
}

template <class T>
void put_le(std::vector<std::byte>& out, T value) {
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        out.push_back(static_cast<std::byte>(static_cast<std::uint64_t>(value) >> (8 * i) & 0xFF));
    }
}

template <class T>
T get_le(const std::byte* in) {
    std::uint64_t value = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        value |= std::uint64_t{static_cast<std::uint8_t>(in[i])} << (8 * i);
    }
    return static_cast<T>(value);
}

std::string errno_text(int error) { return std::strerror(error); }

/// Reads the whole file, up to `limit` + 1 bytes (so that an oversized file shows as such).
/// Sets `error` to errno on failure.
std::optional<std::vector<std::byte>> read_file(const std::string& path, std::size_t limit,
                                                int& error) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        error = errno;
        return std::nullopt;
    }
    std::vector<std::byte> bytes;
    std::array<std::byte, 4096> chunk{};
    while (bytes.size() <= limit) {
        const auto n = ::read(fd, chunk.data(), chunk.size());
        if (n < 0) {
            if (errno == EINTR) continue;
            error = errno;
            ::close(fd);
            return std::nullopt;
        }
        if (n == 0) break;
        bytes.insert(bytes.end(), chunk.begin(), chunk.begin() + n);
    }
    ::close(fd);
    return bytes;
}

/// Exchange names are validated by the configuration, but a path separator must never reach
/// the file system: the file has to stay inside the state directory.
std::string file_name(const std::string& exchange) {
    std::string name = exchange;
    for (auto& c : name) {
        if (c == '/' || c == '\\' || c == '\0') c = '_';
    }
    return name + ".image";
}

}  // namespace

std::uint64_t layout_fingerprint(const core::plan::ExchangePlan& plan) {
    // Only what gives the bytes their meaning: names, limits and topics may change freely.
    std::uint64_t hash = fnv_offset;
    fnv_add(hash, static_cast<std::uint8_t>(plan.length & 0xFF));
    fnv_add(hash, static_cast<std::uint8_t>(plan.length >> 8));
    for (const auto& tag : plan.tags) {
        const auto& address = tag.spec.address;
        fnv_add(hash, static_cast<std::uint8_t>(address.byte & 0xFF));
        fnv_add(hash, static_cast<std::uint8_t>(address.byte >> 8));
        fnv_add(hash, address.bit);
        fnv_add(hash, static_cast<std::uint8_t>(tag.spec.type));
    }
    return hash;
}

ImageStore::ImageStore(std::string directory) : directory_(std::move(directory)) {}

std::string ImageStore::path_of(const core::plan::ExchangePlan& plan) const {
    std::string path = directory_;
    if (!path.empty() && path.back() != '/') path += '/';
    return path + file_name(plan.spec.name);
}

std::optional<std::vector<std::byte>> ImageStore::load(const core::plan::ExchangePlan& plan) const {
    const auto path = path_of(plan);
    const auto& name = plan.spec.name;
    const auto ignored = [&](std::string_view why) {
        spdlog::warn("exchange {}: ignoring saved image {}: {}; initial values apply", name, path,
                     why);
        return std::nullopt;
    };

    int error = 0;
    const auto file = read_file(path, max_file_size, error);
    if (!file) {
        if (error == ENOENT) {
            spdlog::info("exchange {}: no saved image in {}; initial values apply", name, path);
            return std::nullopt;
        }
        return ignored("cannot read it (" + errno_text(error) + ")");
    }
    const auto& bytes = *file;
    if (bytes.size() > max_file_size) return ignored("too large to be an image");
    if (bytes.size() < header_size) return ignored("truncated header");
    if (std::memcmp(bytes.data(), magic.data(), magic.size()) != 0) {
        return ignored("not an eip2mqtt image (bad magic)");
    }
    const std::byte* field = bytes.data() + magic.size();
    const auto version = get_le<std::uint32_t>(field);
    const auto fingerprint = get_le<std::uint64_t>(field + 4);
    const auto length = get_le<std::uint32_t>(field + 12);
    const auto checksum = get_le<std::uint64_t>(field + 16);
    if (version != format_version) {
        return ignored("format version " + std::to_string(version) + ", expected " +
                       std::to_string(format_version));
    }
    if (bytes.size() - header_size < length) {
        return ignored("truncated (" + std::to_string(bytes.size() - header_size) + " of " +
                       std::to_string(length) + " data bytes)");
    }
    if (bytes.size() - header_size > length) return ignored("trailing bytes after the data");
    const std::span<const std::byte> data(bytes.data() + header_size, length);
    if (fnv1a(data) != checksum) return ignored("checksum mismatch (corrupt)");
    if (fingerprint != layout_fingerprint(plan) || length != plan.length) {
        // An expected outcome of a configuration change, not a fault.
        spdlog::info(
            "exchange {}: saved image {} was written for another layout (length, tag addresses "
            "or types changed); initial values apply",
            name, path);
        return std::nullopt;
    }
    return std::vector<std::byte>(data.begin(), data.end());
}

bool ImageStore::save(const core::plan::ExchangePlan& plan, std::span<const std::byte> data) const {
    const auto path = path_of(plan);
    const auto failed = [&](std::string_view step, int error) {
        spdlog::warn("exchange {}: cannot save image {}: {} failed ({}); the previous file is kept",
                     plan.spec.name, path, step, errno_text(error));
        return false;
    };

    // The directory is created on first use (one level), not at construction.
    if (::mkdir(directory_.c_str(), 0755) != 0 && errno != EEXIST) {
        return failed("creating directory " + directory_, errno);
    }

    std::vector<std::byte> bytes;
    bytes.reserve(header_size + data.size());
    for (const char c : magic) bytes.push_back(static_cast<std::byte>(c));
    put_le<std::uint32_t>(bytes, format_version);
    put_le<std::uint64_t>(bytes, layout_fingerprint(plan));
    put_le<std::uint32_t>(bytes, static_cast<std::uint32_t>(data.size()));
    put_le<std::uint64_t>(bytes, fnv1a(data));
    bytes.insert(bytes.end(), data.begin(), data.end());

    const std::span<const std::byte> parts[] = {bytes};
    if (const auto failure = write_file_atomically(path, parts, 0644)) {
        if (failure->replaced) {
            spdlog::warn("exchange {}: saved image {}, but {} failed ({})", plan.spec.name, path,
                         failure->step, errno_text(failure->error));
            return false;
        }
        return failed(failure->step, failure->error);
    }
    return true;
}

void ImageStore::remove(const core::plan::ExchangePlan& plan) const {
    const auto path = path_of(plan);
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) {
        spdlog::warn("exchange {}: cannot remove saved image {}: {}", plan.spec.name, path,
                     errno_text(errno));
    }
}

}  // namespace eip2mqtt::adapters::state
