#include "eip2mqtt/adapters/state/image_store.hpp"

#include <utility>

#include "adapters/state/detail/image_format.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"

namespace eip2mqtt::adapters::state {
namespace {

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
    std::uint64_t hash = detail::fnv_offset;
    detail::fnv_add(hash, static_cast<std::uint8_t>(plan.length & 0xFF));
    detail::fnv_add(hash, static_cast<std::uint8_t>(plan.length >> 8));
    for (const auto& tag : plan.tags) {
        const auto& address = tag.spec.address;
        detail::fnv_add(hash, static_cast<std::uint8_t>(address.byte & 0xFF));
        detail::fnv_add(hash, static_cast<std::uint8_t>(address.byte >> 8));
        detail::fnv_add(hash, address.bit);
        detail::fnv_add(hash, static_cast<std::uint8_t>(tag.spec.type));
    }
    return hash;
}

ImageStore::ImageStore(std::string directory) : directory_(std::move(directory)) {}

std::string ImageStore::path_of(const core::plan::ExchangePlan& plan) const {
    std::string path = directory_;
    if (!path.empty() && path.back() != '/') path += '/';
    return path + file_name(plan.spec.name);
}

std::shared_ptr<ImageFile> ImageStore::open(const core::plan::ExchangePlan& plan) const {
    return std::make_shared<ImageFile>(path_of(plan), plan.spec.name, layout_fingerprint(plan),
                                       plan.length);
}

std::optional<std::vector<std::byte>> ImageStore::load(const core::plan::ExchangePlan& plan) const {
    return open(plan)->loaded();
}

}  // namespace eip2mqtt::adapters::state
