#include "adapters/state/detail/image_format.hpp"

#include <algorithm>
#include <cstring>
#include <string_view>

namespace eip2mqtt::adapters::state::detail {
namespace {

constexpr std::string_view magic = "EIP2MQTT-IMG";
constexpr std::uint64_t fnv_prime = 0x100000001b3ULL;
// magic | version | sequence | fingerprint | length, then the checksum.
constexpr std::size_t slot_checked = 12 + 4 + 8 + 8 + 4;
constexpr std::size_t slot_header = slot_checked + 8;
// magic | version | fingerprint | length | checksum.
constexpr std::size_t whole_header = 12 + 4 + 8 + 4 + 8;
static_assert(slot_header + max_slot_data == slot_size);

template <class T>
void put_le(std::byte* out, T value) {
    for (std::size_t i = 0; i < sizeof(T); ++i) {
        out[i] = static_cast<std::byte>(static_cast<std::uint64_t>(value) >> (8 * i) & 0xFF);
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

}  // namespace

void fnv_add(std::uint64_t& hash, std::uint8_t byte) {
    hash ^= byte;
    hash *= fnv_prime;
}

std::uint64_t fnv1a(std::span<const std::byte> data, std::uint64_t hash) {
    for (const auto b : data) fnv_add(hash, static_cast<std::uint8_t>(b));
    return hash;
}

std::optional<std::uint32_t> format_of(std::span<const std::byte> file) {
    if (file.size() < magic.size() + 4) return std::nullopt;
    if (std::memcmp(file.data(), magic.data(), magic.size()) != 0) return std::nullopt;
    return get_le<std::uint32_t>(file.data() + magic.size());
}

void encode_slot(std::uint64_t sequence, std::uint64_t fingerprint, std::span<const std::byte> data,
                 std::span<std::byte> slot) {
    std::fill(slot.begin(), slot.end(), std::byte{0});
    std::memcpy(slot.data(), magic.data(), magic.size());
    std::byte* field = slot.data() + magic.size();
    put_le<std::uint32_t>(field, format_slotted);
    put_le<std::uint64_t>(field + 4, sequence);
    put_le<std::uint64_t>(field + 12, fingerprint);
    put_le<std::uint32_t>(field + 20, static_cast<std::uint32_t>(data.size()));
    std::copy(data.begin(), data.end(), slot.begin() + slot_header);
    const auto checksum = fnv1a(data, fnv1a(slot.first(slot_checked)));
    put_le<std::uint64_t>(slot.data() + slot_checked, checksum);
}

Decoded decode_slot(std::span<const std::byte> slot) {
    if (slot.size() < slot_size) return core::fail(std::string("truncated slot"));
    if (format_of(slot) != format_slotted) return core::fail(std::string("empty or torn slot"));
    const std::byte* field = slot.data() + magic.size();
    StoredImage image;
    image.sequence = get_le<std::uint64_t>(field + 4);
    image.fingerprint = get_le<std::uint64_t>(field + 12);
    const auto length = get_le<std::uint32_t>(field + 20);
    if (length > max_slot_data) return core::fail(std::string("slot length out of bounds"));
    const auto data = slot.subspan(slot_header, length);
    const auto checksum = get_le<std::uint64_t>(slot.data() + slot_checked);
    if (fnv1a(data, fnv1a(slot.first(slot_checked))) != checksum) {
        return core::fail(std::string("checksum mismatch (corrupt or torn)"));
    }
    image.data.assign(data.begin(), data.end());
    return image;
}

Decoded decode_whole(std::span<const std::byte> file) {
    if (file.size() < whole_header) return core::fail(std::string("truncated header"));
    const std::byte* field = file.data() + magic.size();
    StoredImage image;
    image.fingerprint = get_le<std::uint64_t>(field + 4);
    const auto length = get_le<std::uint32_t>(field + 12);
    const auto checksum = get_le<std::uint64_t>(field + 16);
    const auto stored = file.size() - whole_header;
    if (stored < length) {
        return core::fail("truncated (" + std::to_string(stored) + " of " + std::to_string(length) +
                          " data bytes)");
    }
    if (stored > length) return core::fail(std::string("trailing bytes after the data"));
    const auto data = file.subspan(whole_header, length);
    if (fnv1a(data) != checksum) return core::fail(std::string("checksum mismatch (corrupt)"));
    image.data.assign(data.begin(), data.end());
    return image;
}

}  // namespace eip2mqtt::adapters::state::detail
