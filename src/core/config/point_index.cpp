#include "eip2mqtt/core/config/point_index.hpp"

namespace eip2mqtt::core::config {

PointIndex::PointIndex(const PointList& list) {
    for (std::size_t i = 0; i < list.rows.size(); ++i) rows_[list.rows[i].node].push_back(i);
}

std::span<const std::size_t> PointIndex::rows_of(std::string_view node) const {
    const auto it = rows_.find(node);
    if (it == rows_.end()) return {};
    return it->second;
}

}  // namespace eip2mqtt::core::config
