#include "adapters/mqtt/detail/broker_list.hpp"

namespace eip2mqtt::adapters::mqtt::detail {

namespace {

std::vector<std::optional<BrokerEndpoint>> parse_broker_urls(const std::vector<std::string>& urls) {
    std::vector<std::optional<BrokerEndpoint>> endpoints;
    endpoints.reserve(urls.size());
    for (const auto& url : urls) endpoints.push_back(parse_broker_url(url));
    return endpoints;
}

}  // namespace

BrokerList::BrokerList(const std::vector<std::string>& urls)
    : urls_(urls), endpoints_(parse_broker_urls(urls)) {}

}  // namespace eip2mqtt::adapters::mqtt::detail
