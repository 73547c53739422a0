#pragma once
/// docs/mqtt-api.md: each tag and exchange topic, and the topics subscribed for writes, must
/// belong to one owner. Apart from the validator: the claims of 100,000 tags need care of their
/// own (see the .cpp).

#include <set>

#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::core::config::detail {

/// Adds to `out` one error per topic claimed twice. Exchanges in `skip` (a repeated name,
/// reported already) claim nothing; names and topics that topic_problem or tag_name_problem
/// refuse are skipped likewise.
void check_topic_collisions(const Config& config, const std::set<const ExchangeConfig*>& skip,
                            Diagnostics& out);

}  // namespace eip2mqtt::core::config::detail
