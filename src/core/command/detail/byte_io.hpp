#pragma once
/// Bounds-checked little-endian reads and writes for the command codec. Producer ids and IPv4
/// addresses are the exception: four bytes in dotted order (docs/protocol.md §9.1).

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace eip2mqtt::core::command::detail {

/// Reads from a PDU. Each read past the end returns 0 and marks the reader as overrun, so a
/// decoder reads every field and checks `overrun()` once.
class ByteReader {
public:
    explicit ByteReader(std::span<const std::byte> bytes) : bytes_(bytes) {}

    std::uint8_t u8(std::size_t offset) {
        if (!fits(offset, 1)) return 0;
        return std::to_integer<std::uint8_t>(bytes_[offset]);
    }
    std::uint16_t u16(std::size_t offset) {
        if (!fits(offset, 2)) return 0;
        return static_cast<std::uint16_t>(raw(offset) | raw(offset + 1) << 8);
    }
    std::uint32_t u32(std::size_t offset) {
        if (!fits(offset, 4)) return 0;
        return raw(offset) | raw(offset + 1) << 8 | raw(offset + 2) << 16 |
               std::uint32_t{raw(offset + 3)} << 24;
    }
    std::uint32_t dotted(std::size_t offset) {
        if (!fits(offset, 4)) return 0;
        return std::uint32_t{raw(offset)} << 24 | raw(offset + 1) << 16 | raw(offset + 2) << 8 |
               raw(offset + 3);
    }
    std::span<const std::byte> bytes(std::size_t offset, std::size_t count) {
        if (!fits(offset, count)) return {};
        return bytes_.subspan(offset, count);
    }
    /// Characters from `offset` to the first NUL or the end, at most `limit`.
    std::string text(std::size_t offset, std::size_t limit) {
        std::string out;
        for (std::size_t i = offset; i < bytes_.size() && out.size() < limit; ++i) {
            const auto c = static_cast<char>(raw(i));
            if (c == '\0') break;
            out += c;
        }
        return out;
    }

    std::size_t size() const { return bytes_.size(); }
    bool overrun() const { return overrun_; }

private:
    bool fits(std::size_t offset, std::size_t count) {
        if (offset > bytes_.size() || count > bytes_.size() - offset) overrun_ = true;
        return !overrun_;
    }
    std::uint32_t raw(std::size_t offset) const {
        return std::to_integer<std::uint32_t>(bytes_[offset]);
    }

    std::span<const std::byte> bytes_;
    bool overrun_ = false;
};

/// Appends to a PDU under construction; the caller sized it right (encoders assert it).
class ByteWriter {
public:
    explicit ByteWriter(std::vector<std::byte>& out) : out_(out) {}

    void u8(std::uint32_t value) { out_.push_back(static_cast<std::byte>(value & 0xFF)); }
    void u16(std::uint32_t value) {
        u8(value);
        u8(value >> 8);
    }
    void u32(std::uint32_t value) {
        u16(value);
        u16(value >> 16);
    }
    void dotted(std::uint32_t value) {
        for (int shift = 24; shift >= 0; shift -= 8) u8(value >> shift);
    }
    void bytes(std::span<const std::byte> data) {
        out_.insert(out_.end(), data.begin(), data.end());
    }
    void zeros(std::size_t count) { out_.insert(out_.end(), count, std::byte{0}); }
    /// The characters and one NUL.
    void text(std::string_view value) {
        for (char c : value) u8(static_cast<unsigned char>(c));
        u8(0);
    }

private:
    std::vector<std::byte>& out_;
};

}  // namespace eip2mqtt::core::command::detail
