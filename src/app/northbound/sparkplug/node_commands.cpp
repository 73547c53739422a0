// What hosts send the edge node: NCMD (rebirth), DCMD (writes to a produced exchange's tags) and
// the primary host's STATE. A DCMD goes through the checks of a JSON write (retained, writable,
// type, range, limits, overlapping tags) and reaches the WriteDispatcher as one WriteRequest:
// all its metrics or none, in one datagram.

#include "eip2mqtt/app/northbound/sparkplug/node_commands.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <utility>
#include <variant>
#include <vector>

#include "eip2mqtt/core/plan/published_value.hpp"
#include "eip2mqtt/core/printable.hpp"

namespace eip2mqtt::app::northbound::sparkplug {
namespace {

using core::plan::Value;
using core::write::WriteError;
using core::write::WriteInput;
using core::write::WriteRejection;

constexpr std::string_view rebirth_name = "Node Control/Rebirth";

/// A rebirth request: `Node Control/Rebirth` by name (it has no alias) set to true, with its
/// datatype or without (the form the specification recommends for a command).
bool asks_rebirth(const adapters::sparkplug::CommandMetric& metric) {
    if (metric.name != rebirth_name) return false;
    const auto value =
        metric.datatype ? metric.value : metric.value_as(adapters::sparkplug::DataType::boolean);
    return value && std::holds_alternative<bool>(*value) && std::get<bool>(*value);
}

/// A command's value as a JSON write's would be: integers exactly, a float or double that holds
/// an integer as that integer (WriteInput's contract), others as double.
WriteInput write_input(const Value& value) {
    return std::visit(
        [](const auto& v) -> WriteInput {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::int64_t> ||
                          std::is_same_v<T, std::uint64_t>) {
                return v;
            } else if constexpr (std::is_same_v<T, core::plan::Text>) {
                return *v;
            } else if constexpr (std::is_same_v<T, core::plan::List>) {
                return core::write::ArrayInput{};  // commands carry no arrays: refused by shape
            } else {
                const double d = v;
                if (std::isfinite(d) && std::trunc(d) == d && d >= -0x1p63 && d < 0x1p63) {
                    return static_cast<std::int64_t>(d);
                }
                return d;
            }
        },
        value);
}

/// What a throttled line adds when it sums up more than one occurrence.
std::string in_the_last_minute(std::uint64_t count, std::string_view what) {
    if (count <= 1) return {};
    return " (" + std::to_string(count) + " " + std::string(what) + " since the last line)";
}

/// The writes a DCMD's metrics ask of the produced exchange `plan`, or why they are refused.
std::variant<ExchangeWrite, WriteRejection> device_write(
    const Device& device, const std::vector<adapters::sparkplug::CommandMetric>& metrics) {
    const auto& plan = *device.plan;
    ExchangeWrite write{&plan, {}};
    write.writes.reserve(metrics.size());
    for (const auto& metric : metrics) {
        const auto tag = DeviceRegistry::tag_of(device, metric);
        if (!tag) {
            return WriteRejection{
                WriteError::unknown_tag,
                "unknown metric " +
                    (metric.name.empty() && metric.alias ? "alias " + std::to_string(*metric.alias)
                                                         : metric.name) +
                    " in exchange " + plan.spec.name};
        }
        const auto& spec = plan.tags[*tag].spec;
        // Without a datatype (by alias, as hosts that use aliases send it), the one the tag's
        // metric was born with.
        const auto given = metric.datatype ? metric.value
                                           : metric.value_as(adapters::sparkplug::datatype_of(
                                                 core::plan::published_type(spec)));
        if (!given) {
            return WriteRejection{WriteError::wrong_type,
                                  spec.name + ": no value of a datatype the gateway takes"};
        }
        auto value = core::write::validate_write(spec, write_input(*given));
        if (!value) {
            return WriteRejection{value.error().error, spec.name + ": " + value.error().message};
        }
        write.writes.push_back({*tag, std::move(value).value()});
    }
    if (auto overlap = core::write::overlap_rejection(plan, write.writes)) {
        return std::move(*overlap);
    }
    return write;
}

}  // namespace

NodeCommands::NodeCommands(const std::string& group_id, const std::string& edge_node_id,
                           std::string primary_host_id, WriteHandler& writes, Northbound& origin)
    : ncmd_topic_("spBv1.0/" + group_id + "/NCMD/" + edge_node_id),
      dcmd_prefix_("spBv1.0/" + group_id + "/DCMD/" + edge_node_id + "/"),
      primary_host_id_(std::move(primary_host_id)),
      writes_(writes),
      origin_(origin) {
    if (!primary_host_id_.empty()) state_topic_ = "spBv1.0/STATE/" + primary_host_id_;
}

std::vector<std::string> NodeCommands::subscriptions() const {
    std::vector<std::string> filters{ncmd_topic_, dcmd_prefix_ + "+"};
    if (!state_topic_.empty()) filters.push_back(state_topic_);
    return filters;
}

NodeCommands::Asked NodeCommands::on_message(const adapters::mqtt::Incoming& message,
                                             DeviceRegistry& devices, const NodeSession& session) {
    if (message.topic == ncmd_topic_) return on_node_command(message, session.now());
    if (message.topic.starts_with(dcmd_prefix_)) {
        // An empty DCMD is a retained one being cleared: nothing is asked.
        if (message.payload.empty()) return Asked::nothing;
        on_device_command(message, devices.find(message.topic.substr(dcmd_prefix_.size())),
                          session);
        return Asked::nothing;
    }
    if (!state_topic_.empty() && message.topic == state_topic_) return on_state(message, session);
    return Asked::nothing;
}

NodeCommands::Asked NodeCommands::on_node_command(const adapters::mqtt::Incoming& message,
                                                  core::MonoTime now) {
    const auto metrics = adapters::sparkplug::decode_command(message.payload);
    if (!metrics) {
        if (const auto count = command_log_.record(now)) {
            spdlog::warn("Sparkplug NCMD ignored: {} ({} ignored)", metrics.error(), count);
        }
        return Asked::nothing;
    }
    for (const auto& metric : metrics.value()) {
        if (asks_rebirth(metric)) {
            if (const auto count = rebirth_log_.record(now)) {
                spdlog::info("Sparkplug rebirth requested by NCMD{}",
                             in_the_last_minute(count, "requests"));
            }
            return Asked::rebirth;
        }
    }
    return Asked::nothing;
}

void NodeCommands::on_device_command(const adapters::mqtt::Incoming& message, const Device* device,
                                     const NodeSession& session) {
    WriteRequest request;
    request.reply.origin = &origin_;
    request.reply.via = WriteOrigin::sparkplug;
    request.target = message.topic;
    const auto refuse = [&](WriteError error, std::string text) {
        request.outcome = WriteRejection{error, std::move(text)};
        writes_.on_write(std::move(request));
    };
    const auto device_name = message.topic.substr(dcmd_prefix_.size());
    if (!session.born()) {
        // Sparkplug B 3.0: an edge node that is offline (no NBIRTH since its connection, its
        // primary host's STATE, or after its NDEATH) takes no command.
        if (const auto count = refused_log_.record(session.now())) {
            spdlog::warn("Sparkplug DCMD for {} refused: the edge node is offline (not born){}",
                         core::printable(device_name), in_the_last_minute(count, "refused"));
        }
        return refuse(WriteError::offline, "the Sparkplug edge node is offline (not born)");
    }
    if (!device) return refuse(WriteError::unknown_tag, "no exchange named " + device_name);
    const auto& plan = *device->plan;
    // A retained command would fire again on every reconnect: never act on one.
    if (message.retained) {
        return refuse(WriteError::retained,
                      "retained commands are refused; publish without retain");
    }
    if (!device->produced) {
        return refuse(WriteError::read_only,
                      "exchange " + plan.spec.name + " is consumed: its tags are read-only");
    }
    const auto metrics = adapters::sparkplug::decode_command(message.payload);
    if (!metrics) return refuse(WriteError::malformed, "DCMD: " + metrics.error());
    if (metrics.value().empty()) return refuse(WriteError::empty, "a DCMD with no metric");
    auto write = device_write(*device, metrics.value());
    if (auto* rejection = std::get_if<WriteRejection>(&write)) {
        return refuse(rejection->error, std::move(rejection->message));
    }
    request.outcome = std::move(write);
    writes_.on_write(std::move(request));
}

NodeCommands::Asked NodeCommands::on_state(const adapters::mqtt::Incoming& message,
                                           const NodeSession& session) {
    // Sparkplug B 3.0: {"online": bool, "timestamp": ms}; a STATE older than the last one
    // taken is stale (a retained one delivered after a newer live one) and ignored.
    const auto json = nlohmann::json::parse(message.payload, nullptr, false);
    if (json.is_discarded() || !json.is_object() || !json.contains("online") ||
        !json["online"].is_boolean() || !json.contains("timestamp") ||
        !json["timestamp"].is_number_integer()) {
        if (const auto count = command_log_.record(session.now())) {
            spdlog::warn(
                "Sparkplug STATE of {} ignored: not {{\"online\": bool, \"timestamp\": ms}} "
                "({} ignored)",
                core::printable(primary_host_id_), count);
        }
        return Asked::nothing;
    }
    const auto timestamp = json["timestamp"].get<std::int64_t>();
    if (timestamp < host_state_timestamp_) return Asked::nothing;
    host_state_timestamp_ = timestamp;
    const bool online = json["online"].get<bool>();
    if (online == session.host_online()) return Asked::nothing;
    return host_changed(online, session.now());
}

NodeCommands::Asked NodeCommands::host_changed(bool online, core::MonoTime now) {
    // A host that flaps must not flood the log: the first change, then a summary a minute.
    if (const auto count = state_log_.record(now)) {
        const auto changes = in_the_last_minute(count, "changes of its STATE");
        if (online) {
            spdlog::info("Sparkplug primary host {} is online: births{}",
                         core::printable(primary_host_id_), changes);
        } else {
            spdlog::warn(
                "Sparkplug primary host {} is offline: a born node says its NDEATH, leaves its "
                "broker for the next of mqtt.url and waits there for the host{}",
                core::printable(primary_host_id_), changes);
        }
    }
    return online ? Asked::host_online : Asked::host_offline;
}

void NodeCommands::flush_logs(core::MonoTime now, std::uint64_t node_births, bool host_online) {
    if (const auto count = rebirth_log_.flush(now)) {
        spdlog::info("Sparkplug: {} more rebirth requests by NCMD, coalesced ({} NBIRTHs in all)",
                     count, node_births);
    }
    if (const auto count = state_log_.flush(now)) {
        spdlog::info("Sparkplug primary host {}: {} more STATE changes, now {}", primary_host_id_,
                     count, host_online ? "online" : "offline");
    }
    if (const auto count = refused_log_.flush(now)) {
        spdlog::warn("Sparkplug: {} more DCMDs refused while the edge node is not born", count);
    }
}

}  // namespace eip2mqtt::app::northbound::sparkplug
