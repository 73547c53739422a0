#pragma once
// The bytes of an image file, shared by ImageFile and ImageStore only. Every integer is
// little-endian.
//
// Format 2, two slots, each a whole image in its own 4 KiB block, overwritten in turn:
//   magic "EIP2MQTT-IMG" (12) | format version u32 = 2 | sequence u64 | layout fingerprint u64 |
//   data length u32 | FNV-1a 64 of everything before it and of the data u64 | data | zeros
// The slot with the higher sequence that checks out is the image; a save overwrites the other.
// Its blocks are allocated when the file is created, so a save on a full disk still succeeds
// (where the file system overwrites in place), and a save torn by a power cut leaves the other
// slot, the save before, intact.
//
// Format 1, written by the builds before slots, one image replacing the file whole; read, so
// that an upgrade keeps the last written values, and rewritten as format 2:
//   magic "EIP2MQTT-IMG" (12) | format version u32 = 1 | layout fingerprint u64 |
//   data length u32 | FNV-1a 64 of the data u64 | data

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "eip2mqtt/core/result.hpp"

namespace eip2mqtt::adapters::state::detail {

inline constexpr std::size_t slot_size = 4096;
inline constexpr std::size_t slot_count = 2;
inline constexpr std::size_t slotted_file_size = slot_size * slot_count;
inline constexpr std::uint32_t format_slotted = 2;
inline constexpr std::uint32_t format_whole = 1;
/// The largest image a slot holds: far above any exchange's length (1400 bytes at most).
inline constexpr std::size_t max_slot_data = slot_size - 44;

/// One image as stored: a slot, or a format-1 file (sequence 0).
struct StoredImage {
    std::uint64_t sequence = 0;
    std::uint64_t fingerprint = 0;
    std::vector<std::byte> data;
};

/// An image, or why the bytes are not one (the end of a log line: "checksum mismatch").
using Decoded = core::Result<StoredImage, std::string>;

/// FNV-1a 64: the checksum of both formats, and the layout fingerprint.
inline constexpr std::uint64_t fnv_offset = 0xcbf29ce484222325ULL;
void fnv_add(std::uint64_t& hash, std::uint8_t byte);
std::uint64_t fnv1a(std::span<const std::byte> data, std::uint64_t hash = fnv_offset);

/// The format version of a file that starts with the magic; nullopt when it does not.
std::optional<std::uint32_t> format_of(std::span<const std::byte> file);

/// Writes one slot (slot_size bytes, zero padded) holding `data` (at most max_slot_data bytes).
void encode_slot(std::uint64_t sequence, std::uint64_t fingerprint, std::span<const std::byte> data,
                 std::span<std::byte> slot);
/// Reads one slot; an error for zeros, a torn or a corrupt slot.
Decoded decode_slot(std::span<const std::byte> slot);
/// Reads a whole format-1 file.
Decoded decode_whole(std::span<const std::byte> file);

}  // namespace eip2mqtt::adapters::state::detail
