// A Tree on disk, with the text it was parsed from, so that an unchanged configuration is not
// parsed again (see tree.hpp). The file is machine-local: integers are native, and the header
// names the format, the entry size and the eip2mqtt version that wrote it; anything else is
// ignored rather than trusted. Layout: header | text, zero-padded to 8 bytes | nodes (Entry) |
// children (u32) | scalars; a loaded Tree views the mapped file in place.

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <memory>
#include <type_traits>

#include "adapters/yaml/detail/tree.hpp"
#include "eip2mqtt/adapters/state/atomic_file.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

/// Bump when Builder (tree.cpp) or Entry change what a text turns into: an old file then no
/// longer matches, whatever the version string says.
constexpr std::uint32_t kFormat = 2;
constexpr std::array<char, 8> kMagic = {'E', 'I', 'P', '2', 'T', 'R', 'E', 'E'};

struct Header {
    std::array<char, 8> magic = kMagic;
    std::uint32_t format = kFormat;
    std::uint32_t entry_size = 0;
    std::array<char, 32> version = {};  ///< EIP2MQTT_VERSION of the writer, zero-padded
    std::uint64_t text_size = 0;        ///< of the source text, stored after the header
    std::uint64_t nodes = 0;
    std::uint64_t children = 0;
    std::uint64_t scalars = 0;  ///< bytes of Tree::text_
    std::uint32_t root = 0;
    std::uint32_t has_root = 0;
};
static_assert(std::has_unique_object_representations_v<Header>, "saved as it is");
static_assert(sizeof(Header) % 8 == 0, "the arrays after it stay aligned");

std::array<char, 32> this_version() {
    std::array<char, 32> version = {};
    const std::string_view text = EIP2MQTT_VERSION;
    std::memcpy(version.data(), text.data(), std::min(text.size(), version.size()));
    return version;
}

/// Rounds `size` up to a multiple of 8, so that the arrays after the text are aligned.
constexpr std::uint64_t padded(std::uint64_t size) { return (size + 7) / 8 * 8; }

/// A file mapped read-only for as long as a loaded Tree views it. The cache file is only ever
/// replaced by a rename (a new file), never rewritten in place, so the mapping stays valid.
class Mapping {
public:
    Mapping(const void* data, std::size_t size) : data_(data), size_(size) {}
    ~Mapping() { ::munmap(const_cast<void*>(data_), size_); }
    Mapping(const Mapping&) = delete;
    Mapping& operator=(const Mapping&) = delete;

    const char* bytes() const { return static_cast<const char*>(data_); }
    std::size_t size() const { return size_; }

private:
    const void* data_;
    std::size_t size_;
};

/// `path` mapped whole, or null with `why` set (empty when the file does not exist).
std::shared_ptr<const Mapping> map_file(const std::filesystem::path& path, std::string& why) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        if (errno != ENOENT) why = std::string("cannot open it: ") + std::strerror(errno);
        return nullptr;
    }
    struct stat st {};
    void* data = MAP_FAILED;
    if (::fstat(fd, &st) != 0) {
        why = std::string("cannot stat it: ") + std::strerror(errno);
    } else if (static_cast<std::uint64_t>(st.st_size) < sizeof(Header)) {
        why = "not a saved tree";
    } else {
        // MAP_POPULATE: every page is read anyway (the text compared, each index checked).
        data = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ,
                      MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (data == MAP_FAILED) why = std::string("cannot map it: ") + std::strerror(errno);
    }
    ::close(fd);
    if (data == MAP_FAILED) return nullptr;
    return std::make_shared<const Mapping>(data, static_cast<std::size_t>(st.st_size));
}

}  // namespace

bool Tree::consistent() const {
    if (has_root_ && root_ >= nodes_.size()) return false;
    for (const auto& node : nodes_) {
        const std::uint64_t end = std::uint64_t{node.first} + node.count;
        switch (node.kind) {
            case Kind::null:
                break;
            case Kind::scalar:
                if (end > text_.size()) return false;
                break;
            case Kind::map:
                if (node.count % 2 != 0) return false;
                [[fallthrough]];
            case Kind::sequence:
                if (end > children_.size()) return false;
                break;
            default:
                return false;
        }
    }
    for (const auto child : children_) {
        if (child >= nodes_.size()) return false;
    }
    return true;
}

std::optional<Tree> Tree::load(const std::filesystem::path& file, std::string_view text,
                               std::string& why) {
    why.clear();
    const auto mapping = map_file(file, why);
    if (!mapping) return std::nullopt;
    Header header;
    std::memcpy(&header, mapping->bytes(), sizeof header);
    if (header.magic != kMagic) {
        why = "not a saved tree";
        return std::nullopt;
    }
    if (header.format != kFormat || header.entry_size != sizeof(Entry) ||
        header.version != this_version()) {
        why = "written by another version";
        return std::nullopt;
    }
    if (header.text_size != text.size()) {
        why = "the configuration changed";
        return std::nullopt;
    }
    // Sizes are checked against the file before any array is looked at.
    const std::uint64_t limit = mapping->size();
    if (header.nodes > limit / sizeof(Entry) || header.children > limit / 4 ||
        header.scalars > limit ||
        sizeof header + padded(header.text_size) + header.nodes * sizeof(Entry) +
                header.children * 4 + header.scalars !=
            limit) {
        why = "damaged (its sizes do not add up)";
        return std::nullopt;
    }
    const char* at = mapping->bytes() + sizeof header;
    if (std::memcmp(at, text.data(), text.size()) != 0) {
        why = "the configuration changed";
        return std::nullopt;
    }
    at += padded(header.text_size);
    Tree tree;
    tree.nodes_ = {reinterpret_cast<const Entry*>(at), header.nodes};
    at += header.nodes * sizeof(Entry);
    tree.children_ = {reinterpret_cast<const std::uint32_t*>(at), header.children};
    at += header.children * 4;
    tree.text_ = {at, header.scalars};
    tree.root_ = header.root;
    tree.has_root_ = header.has_root != 0;
    tree.storage_ = mapping;
    if (!tree.consistent()) {
        why = "damaged (its nodes are inconsistent)";
        return std::nullopt;
    }
    return tree;
}

std::string Tree::save(const std::filesystem::path& file, std::string_view text) const {
    static_assert(std::has_unique_object_representations_v<Entry>, "saved as it is");
    Header header;
    header.entry_size = sizeof(Entry);
    header.version = this_version();
    header.text_size = text.size();
    header.nodes = nodes_.size();
    header.children = children_.size();
    header.scalars = text_.size();
    header.root = root_;
    header.has_root = has_root_ ? 1 : 0;
    const std::array<std::byte, 8> zeros{};
    const std::span<const std::byte> parts[] = {
        std::as_bytes(std::span(&header, 1)),
        std::as_bytes(std::span(text)),
        std::span(zeros).first(padded(text.size()) - text.size()),
        std::as_bytes(nodes_),
        std::as_bytes(children_),
        std::as_bytes(std::span(text_))};
    const auto failure = state::write_file_atomically(file.string(), parts, 0600);
    if (!failure || failure->replaced) return {};  // a cache needs no durability
    return failure->step + ": " + std::strerror(failure->error);
}

}  // namespace eip2mqtt::adapters::yaml::detail
