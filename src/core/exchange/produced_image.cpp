#include "eip2mqtt/core/exchange/produced_image.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <chrono>
#include <iterator>
#include <utility>

#include "eip2mqtt/core/plan/value_codec.hpp"
#include "eip2mqtt/core/wire/encode.hpp"

namespace eip2mqtt::core::exchange {

ProducedImage::ProducedImage(const plan::ExchangePlan& plan, std::span<const std::byte> restored,
                             std::size_t max_pending)
    : plan_(&plan), data_(plan.length), max_pending_(max_pending) {
    if (!restored.empty() && restored.size() == plan.length) {
        std::copy(restored.begin(), restored.end(), data_.begin());
        restored_ = true;
        return;
    }
    // A missing image, or one saved under another length, starts from zeros plus `initial`.
    for (const auto& tag : plan.tags) {
        if (const auto& initial = tag.spec.initial()) {
            plan::encode_tag(data_, tag.spec, *initial);
        }
    }
}

bool ProducedImage::stage(write::WriteBatch batch) {
    if (pending_.size() >= max_pending_) return false;
    pending_.push_back(std::move(batch));
    return true;
}

void ProducedImage::discard_pending(std::vector<std::uint64_t>& dropped) {
    for (const auto& batch : pending_) dropped.push_back(batch.id);
    pending_.clear();
}

void ProducedImage::take_pending(std::vector<write::WriteBatch>& taken) {
    std::move(pending_.begin(), pending_.end(), std::back_inserter(taken));
    pending_.clear();
}

void ProducedImage::discard_pending(std::uint64_t after, std::uint64_t through,
                                    std::vector<std::uint64_t>& dropped) {
    const auto first = std::find_if(pending_.begin(), pending_.end(),
                                    [&](const auto& batch) { return batch.id > after; });
    const auto last =
        std::find_if(first, pending_.end(), [&](const auto& batch) { return batch.id > through; });
    for (auto it = first; it != last; ++it) dropped.push_back(it->id);
    pending_.erase(first, last);
}

bool ProducedImage::apply(const write::WriteBatch& batch, std::span<std::byte> data) const {
    bool changed = false;
    for (const auto& write : batch.writes) {
        assert(write.tag_index < plan_->tags.size());
        const auto& tag = plan_->tags[write.tag_index].spec;
        const auto bytes = data.subspan(tag.address.byte, plan::tag_size(tag));
        // A scalar's bytes on the stack; an array's or a string's (at most 1,400) on the heap.
        std::array<std::byte, 8> small{};
        std::vector<std::byte> large;
        if (bytes.size() > small.size()) large.resize(bytes.size());
        const std::span<std::byte> before =
            large.empty() ? std::span(small).first(bytes.size()) : std::span(large);
        std::copy(bytes.begin(), bytes.end(), before.begin());
        if (write.element) {
            plan::encode_value(data, tag.type, plan::element_address(tag, *write.element),
                               write.value);
        } else {
            plan::encode_tag(data, tag, write.value);
        }
        if (!std::equal(bytes.begin(), bytes.end(), before.begin())) changed = true;
    }
    return changed;
}

bool ProducedImage::holds(std::span<const write::TagWrite> writes) const {
    auto scratch = data_;
    return !apply({0, {writes.begin(), writes.end()}}, scratch);
}

bool ProducedImage::adopt(std::span<const std::byte> data) {
    if (data.size() != data_.size() || std::equal(data.begin(), data.end(), data_.begin())) {
        return false;
    }
    std::copy(data.begin(), data.end(), data_.begin());
    return true;
}

void ProducedImage::continue_after(std::uint16_t heard) {
    // docs/protocol.md §2: +1 per datagram, wrapping; consumers see one producer go on.
    request_id_ = static_cast<std::uint16_t>(heard + 1);
}

std::uint64_t ProducedImage::project(std::vector<std::byte>& out) const {
    out.assign(data_.begin(), data_.end());
    for (const auto& batch : pending_) apply(batch, out);
    return pending_.empty() ? 0 : pending_.back().id;
}

std::size_t ProducedImage::produce(WallTime wall, std::span<std::byte> out,
                                   std::vector<std::uint64_t>& carried, std::uint64_t through) {
    // docs/mqtt-api.md "Several tags at once": whole batches between two productions, so one
    // datagram never carries half a multi-tag write.
    while (!pending_.empty() && pending_.front().id <= through) {
        if (apply(pending_.front(), data_)) dirty_ = true;
        carried.push_back(pending_.front().id);
        pending_.pop_front();
    }

    // docs/protocol.md §5: the time at which the image was sampled, as seconds + nanoseconds.
    const auto sampled = wire_time(wall);

    wire::Header header;
    header.pdu_type = wire::pdu_type_data;
    header.pdu_version = wire::pdu_version;
    header.request_id = request_id_;
    header.producer_id = plan_->spec.producer_id;
    header.exchange_id = plan_->spec.exchange_id;
    header.time_s = sampled.seconds;
    header.time_ns = sampled.nanoseconds;
    header.status = 0;
    header.signature = plan_->spec.signature.to_wire();
    header.reserved = 0;
    const std::size_t size = wire::encode_datagram(header, data_, out);

    // §5: one counter per exchange, +1 per datagram, wrapping 65535 -> 0.
    request_id_ = static_cast<std::uint16_t>(request_id_ + 1);
    return size;
}

}  // namespace eip2mqtt::core::exchange
