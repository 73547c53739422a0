#include "eip2mqtt/core/command/write_plan.hpp"

#include <algorithm>
#include <cstdint>

#include "eip2mqtt/core/plan/value_codec.hpp"

namespace eip2mqtt::core::command {
namespace {

using Bits = std::vector<std::uint8_t>;  // one byte of bits per data byte

// The bits a tag occupies, OR-ed into `bits`.
void mark_tag(Bits& bits, const plan::TagSpec& tag) {
    if (tag.type == plan::TagType::bit) {
        for (std::size_t i = 0; i < tag.count; ++i) {
            const auto at = plan::element_address(tag, i);
            if (at.byte < bits.size()) bits[at.byte] |= static_cast<std::uint8_t>(1u << at.bit);
        }
        return;
    }
    const auto end = std::min<std::size_t>(tag.address.byte + plan::tag_size(tag), bits.size());
    for (std::size_t i = tag.address.byte; i < end; ++i) bits[i] = 0xFF;
}

bool intersects(const Bits& written, const plan::TagSpec& tag) {
    Bits mine(written.size(), 0);
    mark_tag(mine, tag);
    for (std::size_t i = 0; i < written.size(); ++i) {
        if ((mine[i] & written[i]) != 0) return true;
    }
    return false;
}

}  // namespace

Result<std::vector<write::TagWrite>, WriteRefusal> plan_write(const plan::ExchangePlan& plan,
                                                              std::span<const std::byte> image,
                                                              const DataPdu& pdu, bool masked) {
    std::vector<std::byte> next(image.begin(), image.end());
    next.resize(plan.length);
    Bits written(plan.length, 0);
    for (const auto& cell : pdu.cells) {
        for (std::size_t i = 0; i < cell.length; ++i) {
            const auto at = cell.offset + i;
            const auto mask = masked ? std::to_integer<std::uint8_t>(cell.mask[i]) : 0xFF;
            const auto old = std::to_integer<std::uint8_t>(next[at]);
            const auto data = std::to_integer<std::uint8_t>(cell.data[i]);
            next[at] = static_cast<std::byte>((old & ~mask) | (data & mask));
            written[at] |= static_cast<std::uint8_t>(mask);
        }
    }
    Bits writable(plan.length, 0);
    for (const auto& tag : plan.tags) {
        if (tag.spec.writable) mark_tag(writable, tag.spec);
    }
    for (std::size_t i = 0; i < written.size(); ++i) {
        if ((written[i] & ~writable[i]) != 0)
            return fail(WriteRefusal{CommandStatus::not_permitted, std::nullopt});
    }
    std::vector<write::TagWrite> writes;
    for (std::size_t index = 0; index < plan.tags.size(); ++index) {
        const auto& tag = plan.tags[index].spec;
        if (!tag.writable || !intersects(written, tag)) continue;
        // A string as its bytes are, padding too: the command port writes raw bytes.
        const auto value = plan::decode_tag(next, tag, plan::Padding::keep);
        auto checked = write::validate_raw_write(tag, value);
        if (!checked) return fail(WriteRefusal{CommandStatus::rejected, checked.error()});
        writes.push_back({index, std::move(checked).value()});
    }
    if (auto overlap = write::overlap_rejection(plan, writes)) {
        return fail(WriteRefusal{CommandStatus::rejected, std::move(*overlap)});
    }
    return writes;
}

}  // namespace eip2mqtt::core::command
