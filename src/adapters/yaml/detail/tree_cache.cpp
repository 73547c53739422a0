// A Tree on disk, with the text it was parsed from, so that an unchanged configuration is not
// parsed again (see tree.hpp). The file is machine-local: integers are native, and the header
// names the format, the entry size and the eip2mqtt version that wrote it; anything else is
// ignored rather than trusted.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <type_traits>

#include "adapters/yaml/detail/tree.hpp"
#include "eip2mqtt/adapters/state/atomic_file.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

/// Bump when Builder (tree.cpp) or Entry change what a text turns into: an old file then no
/// longer matches, whatever the version string says.
constexpr std::uint32_t kFormat = 1;
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

std::array<char, 32> this_version() {
    std::array<char, 32> version = {};
    const std::string_view text = EIP2MQTT_VERSION;
    std::memcpy(version.data(), text.data(), std::min(text.size(), version.size()));
    return version;
}

class File {
public:
    explicit File(const std::filesystem::path& path)
        : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {}
    ~File() {
        if (fd_ >= 0) ::close(fd_);
    }
    File(const File&) = delete;
    File& operator=(const File&) = delete;

    bool is_open() const { return fd_ >= 0; }
    std::uint64_t size() const {
        struct stat st {};
        return ::fstat(fd_, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
    }

    /// Reads exactly `size` bytes; false on an error or a short file.
    bool read(void* data, std::size_t size) {
        auto* out = static_cast<char*>(data);
        while (size > 0) {
            const auto n = ::read(fd_, out, size);
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) return false;
            out += n;
            size -= static_cast<std::size_t>(n);
        }
        return true;
    }

    /// Whether the next bytes are `expected`, read in chunks (an edited file differs early).
    bool read_equal(std::string_view expected) {
        std::array<char, 64 * 1024> chunk;
        while (!expected.empty()) {
            const auto n = std::min(expected.size(), chunk.size());
            if (!read(chunk.data(), n) || std::memcmp(chunk.data(), expected.data(), n) != 0) {
                return false;
            }
            expected.remove_prefix(n);
        }
        return true;
    }

private:
    int fd_;
};

template <class T>
std::span<const std::byte> bytes_of(const std::vector<T>& items) {
    return std::as_bytes(std::span(items));
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
    File in(file);
    if (!in.is_open()) {
        if (errno != ENOENT) why = std::string("cannot open it: ") + std::strerror(errno);
        return std::nullopt;
    }
    Header header;
    if (!in.read(&header, sizeof header) || header.magic != kMagic) {
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
    // Sizes are checked against the file before anything is allocated for them.
    const std::uint64_t limit = in.size();
    if (header.nodes > limit / sizeof(Entry) || header.children > limit / 4 ||
        header.scalars > limit ||
        sizeof header + header.text_size + header.nodes * sizeof(Entry) + header.children * 4 +
                header.scalars !=
            limit) {
        why = "damaged (its sizes do not add up)";
        return std::nullopt;
    }
    if (!in.read_equal(text)) {
        why = "the configuration changed";
        return std::nullopt;
    }
    Tree tree;
    tree.nodes_.resize(header.nodes);
    tree.children_.resize(header.children);
    tree.text_.resize(header.scalars);
    tree.root_ = header.root;
    tree.has_root_ = header.has_root != 0;
    if (!in.read(tree.nodes_.data(), tree.nodes_.size() * sizeof(Entry)) ||
        !in.read(tree.children_.data(), tree.children_.size() * 4) ||
        !in.read(tree.text_.data(), tree.text_.size()) || !tree.consistent()) {
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
    const std::span<const std::byte> parts[] = {
        std::as_bytes(std::span(&header, 1)), std::as_bytes(std::span(text)), bytes_of(nodes_),
        bytes_of(children_), std::as_bytes(std::span(text_))};
    const auto failure = state::write_file_atomically(file.string(), parts, 0600);
    if (!failure || failure->replaced) return {};  // a cache needs no durability
    return failure->step + ": " + std::strerror(failure->error);
}

}  // namespace eip2mqtt::adapters::yaml::detail
