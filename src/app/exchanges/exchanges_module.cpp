#include "eip2mqtt/app/exchanges/exchanges_module.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <system_error>

namespace eip2mqtt::app {
namespace {

std::vector<adapters::udp::MulticastMembership> memberships(
    const std::vector<core::config::MulticastGroup>& groups) {
    std::vector<adapters::udp::MulticastMembership> out;
    for (const auto& group : groups) out.push_back({group.group, group.interface});
    return out;
}

ExchangesOptions with_socket(const core::config::Config& config, ExchangesOptions options) {
    options.sender.bind = config.eip.bind;
    options.sender.multicast_ttl = config.eip.multicast_ttl;
    options.sender.multicast_interface = config.eip.multicast_interface;
    options.port = config.eip.port;
    options.state_dir = config.gateway.state_dir;
    return options;
}

adapters::udp::ReceiverOptions receiver_options(const core::config::EipSection& eip,
                                                const core::Clock& clock) {
    adapters::udp::ReceiverOptions options;
    options.bind = eip.bind;
    options.port = eip.port;
    options.multicast = memberships(eip.multicast);
    options.clock = &clock;
    return options;
}

}  // namespace

ExchangesModule::ExchangesModule(const core::config::Config& config,
                                 boost::asio::any_io_executor loop, const core::Clock& clock,
                                 ExchangesOptions options)
    : clock_(clock),
      multicast_(config.eip.multicast),
      writes_([this](ExchangeWrite&& write, const WriteReply& reply,
                     core::MonoTime now) { return exchanges_.stage(std::move(write), reply, now); },
              north_, clock),
      exchanges_(loop, with_socket(config, std::move(options)), north_, writes_.image_saves(),
                 clock),
      receiver_(loop, receiver_options(config.eip, clock)) {
    north_.set_write_log(writes_.write_log(), clock);
}

std::string ExchangesModule::apply_plans(std::vector<core::plan::ExchangePlan> plans) {
    const auto report = exchanges_.apply(std::move(plans), clock_.monotonic(), clock_.wall());
    writes_.count_cancelled(report.cancelled_writes);
    return fmt::format(
        "configuration applied: {} exchange(s) kept, {} started, {} stopped ({}); {} retained "
        "topic(s) cleared",
        report.kept.size(), report.started.size(), report.stopped.size(), report.changes,
        report.cleared_topics);
}

void ExchangesModule::start(core::MonoTime now) {
    exchanges_.start(now);
    receiver_.start(
        [this](std::span<const std::byte> bytes, const adapters::udp::Endpoint& from,
               bool truncated) { exchanges_.route(bytes, from, truncated, clock_.monotonic()); });
}

void ExchangesModule::tick(const TickTimes& times) {
    receiver_.read_pending();
    // Judged after what was just read arrived: a time taken before it would be older.
    exchanges_.tick(clock_.monotonic(), times.wall, times.refresh_scan);
}

void ExchangesModule::stop() {
    receiver_.stop();
    exchanges_.stop();
}

bool ExchangesModule::prepare(const core::config::Config& next) {
    if (next.eip.multicast == multicast_) return true;
    try {
        receiver_.set_multicast(memberships(next.eip.multicast));
    } catch (const std::system_error& e) {
        spdlog::error("reload refused: eip.multicast: {}; the running configuration is kept",
                      e.what());
        return false;
    }
    multicast_ = next.eip.multicast;
    return true;
}

}  // namespace eip2mqtt::app
