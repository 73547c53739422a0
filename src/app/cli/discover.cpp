// `eip2mqtt discover HOST...`: asks each node on UDP 7937 (docs/protocol.md §9) for its
// Capabilities, every page of its Summary, and the Retrieve Configuration of each exchange; prints
// a table per node, or with --yaml the skeletons of the exchanges the nodes produce.

#include <cstdio>
#include <ostream>
#include <string>

#include "app/cli/detail/command_requester.hpp"
#include "eip2mqtt/adapters/yaml/discovered_skeleton.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/logging.hpp"
#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::app {
namespace {

using adapters::yaml::DiscoveredExchange;
using adapters::yaml::DiscoveredNode;
using core::command::ExchangeMode;

// Every page of the Summary, from index 0 until the node's total or the index's last value.
void list_exchanges(detail::CommandRequester& requester, const adapters::udp::Endpoint& node,
                    DiscoveredNode& out) {
    std::size_t index = 0;
    while (index <= 255) {
        auto page =
            requester.ask(core::command::SummaryRequest{static_cast<std::uint8_t>(index)}, node);
        if (!page) {
            if (index == 0) out.problem = "Summary: " + page.error();
            return;
        }
        const auto& summary = std::get<core::command::SummaryPage>(page->body);
        out.total = summary.total_cells;
        for (const auto& cell : summary.cells) out.exchanges.push_back({cell, std::nullopt, {}});
        index += summary.cells.size();
        if (summary.cells.empty() || index >= summary.total_cells) return;
    }
}

DiscoveredNode discover_node(detail::CommandRequester& requester,
                             const adapters::udp::Endpoint& node) {
    DiscoveredNode out;
    out.address = adapters::udp::to_string(node);
    auto capabilities = requester.ask(core::command::CapabilitiesRequest{}, node);
    if (capabilities) {
        out.capabilities = std::get<core::command::Capabilities>(capabilities->body);
    } else if (capabilities.error().starts_with(requester.no_answer())) {
        out.problem = capabilities.error();
        return out;
    }
    list_exchanges(requester, node, out);
    for (auto& exchange : out.exchanges) {
        auto config = requester.ask(core::command::RetrieveConfigRequest{exchange.cell.key}, node);
        if (config) {
            exchange.config = std::get<core::command::ExchangeConfig>(config->body);
        } else {
            exchange.problem = config.error();
        }
    }
    return out;
}

// What a node told, as it may reach a terminal: no escape sequence, no line of its own.
std::string told(std::string_view text) { return core::printable_ascii(text, 400); }

std::string cell(std::string text, std::size_t width) {
    if (text.size() < width) text.resize(width, ' ');
    return text + "  ";
}

std::string destination_text(const core::command::ExchangeConfig& config) {
    const auto address = core::wire::to_string(core::wire::ProducerId{config.destination});
    switch (config.destination_type) {
        case core::command::DestinationType::unicast:
            return address;
        case core::command::DestinationType::broadcast:
            return address + " (broadcast)";
        case core::command::DestinationType::multicast:
            return address + " (multicast)";
        default:
            return "-";
    }
}

void print_exchange(const DiscoveredExchange& e, std::ostream& out) {
    out << "  " << cell(core::wire::to_string(e.cell.key.producer_id), 15)
        << cell(std::to_string(e.cell.key.exchange_id), 10);
    if (!e.config) {
        out << "not retrieved: " << told(e.problem) << "\n";
        return;
    }
    const auto& c = *e.config;
    out << cell(c.mode == ExchangeMode::produced ? "produced" : "consumed", 8)
        << cell(std::to_string(c.period_ms), 9) << cell(std::to_string(c.length), 6)
        << cell(destination_text(c), 27) << cell(std::to_string(c.port), 5)
        << cell(core::wire::to_string(core::wire::Signature::from_wire(c.signature)), 9)
        << (c.state == core::command::ExchangeState::active ? "active" : "idle") << "\n";
}

void print_node(const DiscoveredNode& node, std::ostream& out) {
    out << node.address << ": ";
    if (!node.problem.empty()) {
        out << told(node.problem) << "\n";
        return;
    }
    out << (node.capabilities ? "\"" + told(node.capabilities->identification) + "\"" : "?") << ", "
        << node.total << (node.total == 1 ? " exchange" : " exchanges") << "\n";
    if (node.exchanges.empty()) return;
    out << "  " << cell("producer_id", 15) << cell("exchange", 10) << cell("mode", 8)
        << cell("period_ms", 9) << cell("length", 6) << cell("destination", 27) << cell("port", 5)
        << cell("signature", 9) << "state\n";
    for (const auto& exchange : node.exchanges) print_exchange(exchange, out);
}

bool complete(const DiscoveredNode& node) {
    if (!node.problem.empty() || node.exchanges.size() < node.total) return false;
    for (const auto& exchange : node.exchanges) {
        if (!exchange.config) return false;
    }
    return true;
}

}  // namespace

int run_discover(const DiscoverOptions& options, std::ostream& out, std::ostream& err) {
    setup_logging("warn");
    std::vector<adapters::udp::Endpoint> nodes;
    for (const auto& host : options.hosts) {
        const auto node =
            adapters::udp::resolve_endpoint(host, static_cast<std::uint16_t>(options.port));
        if (!node) {
            err << "eip2mqtt discover: cannot resolve " << host << "\n";
            return 2;
        }
        nodes.push_back(*node);
    }
    detail::CommandRequester requester(std::chrono::milliseconds(options.timeout_ms),
                                       options.attempts);
    std::vector<DiscoveredNode> found;
    bool all = true;
    for (const auto& node : nodes) {
        found.push_back(discover_node(requester, node));
        all = all && complete(found.back());
        if (!options.yaml) print_node(found.back(), out);
    }
    if (options.yaml) out << adapters::yaml::discovered_skeleton(found);
    return all ? 0 : 1;
}

}  // namespace eip2mqtt::app
