// MQTT writes (product.md "MQTT"; issue #3): a message on a `…/set` topic is checked whole
// (retained, tag, payload, type, range) and either staged on its produced exchange, whose
// result is published once the datagram carrying it has left, or rejected at once with a
// reason. Nothing is changed by a rejected write, and one bad value rejects a multi-tag write.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <nlohmann/json.hpp>
#include <set>

#include "eip2mqtt/adapters/mqtt/write_payload.hpp"
#include "eip2mqtt/app/gateway.hpp"

namespace eip2mqtt::app {
namespace {

using core::write::WriteError;
using core::write::WriteRejection;

// Rejected writes are logged at most this often (each is answered and counted regardless).
constexpr auto write_log_interval = std::chrono::seconds(10);

constexpr std::string_view set_suffix = "/set";

}  // namespace

void Gateway::build_write_routes() {
    auto add_exchange = [&](const core::plan::ExchangePlan& plan, ExchangeProducer* producer) {
        const WriteRoute route{producer, &plan, plan.spec.name, -1, plan.set_topic + "/result"};
        exchange_routes_[plan.topic] = route;
        write_routes_[plan.set_topic] = route;
    };
    for (const auto& consumer : consumers_) add_exchange(consumer->plan(), nullptr);
    for (const auto& producer : producers_) add_exchange(producer->plan(), producer.get());
}

std::vector<std::string> Gateway::write_subscriptions() const {
    // One filter per depth of `…/set` topic (`{base}/+/+/set`...) rather than one per tag or
    // exchange: a few SUBSCRIBEs for any configuration size, every tag's `/set` is heard
    // (unknown and read-only tags get a reasoned rejection rather than silence), and none of
    // our own publications match, since tag names cannot be `set`.
    const auto base_levels =
        std::count(config_.mqtt.base_topic.begin(), config_.mqtt.base_topic.end(), '/') + 1;
    std::set<long> depths;
    for (const auto& [topic, route] : exchange_routes_) {
        const long levels = std::count(topic.begin(), topic.end(), '/') + 1 - base_levels;
        depths.insert(levels + 1);                                 // {exchange topic}/set
        if (!route.plan->tags.empty()) depths.insert(levels + 2);  // {exchange topic}/{tag}/set
    }
    std::vector<std::string> filters;
    for (const auto depth : depths) {
        std::string filter = config_.mqtt.base_topic;
        for (long i = 1; i < depth; ++i) filter += "/+";
        filters.push_back(filter + "/set");
    }
    return filters;
}

void Gateway::reject_write(const WriteReply& reply, const std::string& target,
                           const WriteRejection& rejection) {
    ++counters_.writes_rejected[static_cast<std::size_t>(rejection.error)];
    const nlohmann::json result = {{"ok", false}, {"error", rejection.message}};
    mqtt_->publish({reply.topic, result.dump(), 1, false, false, reply.correlation_data});
    const auto now = std::chrono::steady_clock::now();
    if (now - last_write_log_ >= write_log_interval) {
        last_write_log_ = now;
        spdlog::warn("write to {} rejected: {} ({} rejected so far)", target, rejection.message,
                     [&] {
                         std::uint64_t total = 0;
                         for (const auto n : counters_.writes_rejected) total += n;
                         return total;
                     }());
    }
}

void Gateway::on_message(adapters::mqtt::Incoming message) {
    const std::string_view topic = message.topic;
    if (!topic.ends_with(set_suffix)) return;

    WriteRoute route;
    std::string tag_name;  ///< set when the tag does not exist
    if (const auto it = write_routes_.find(message.topic); it != write_routes_.end()) {
        route = it->second;
    } else {
        // `{exchange topic}/{name}/set`: tag names hold no '/', so the exchange topic is what
        // comes before the last level, and the tag is found by its name in that exchange.
        const auto stem = topic.substr(0, topic.size() - set_suffix.size());
        const auto slash = stem.rfind('/');
        if (slash == std::string_view::npos) return;
        const auto exchange = exchange_routes_.find(std::string(stem.substr(0, slash)));
        if (exchange == exchange_routes_.end()) return;
        route = exchange->second;
        route.result_topic = message.topic + "/result";
        const auto name = stem.substr(slash + 1);
        const auto& tags = route.plan->tags;
        const auto tag = std::find_if(tags.begin(), tags.end(),
                                      [&](const auto& t) { return t.spec.name == name; });
        if (tag == tags.end()) {
            tag_name = std::string(name);
        } else {
            route.tag_index = static_cast<int>(tag - tags.begin());
        }
    }
    WriteReply reply{message.response_topic.empty() ? route.result_topic : message.response_topic,
                     message.correlation_data};
    auto reject = [&](WriteError error, std::string text) {
        reject_write(reply, message.topic, WriteRejection{error, std::move(text)});
    };
    if (!tag_name.empty()) {
        return reject(WriteError::unknown_tag,
                      "unknown tag " + tag_name + " in exchange " + route.exchange);
    }
    // A retained command would fire again on every reconnect: never act on one.
    if (message.retained) {
        return reject(WriteError::retained, "retained writes are refused; publish without retain");
    }
    if (route.producer == nullptr) {
        return reject(WriteError::read_only,
                      "exchange " + route.exchange + " is consumed: its tags are read-only");
    }
    const auto& plan = route.producer->plan();

    std::vector<core::write::TagWrite> writes;
    auto add = [&](std::size_t index, const core::write::WriteInput& input) -> bool {
        const auto& tag = plan.tags[index].spec;
        auto value = core::write::validate_write(tag, input);
        if (!value) {
            auto rejection = value.error();
            if (route.tag_index < 0) rejection.message = tag.name + ": " + rejection.message;
            reject_write(reply, message.topic, rejection);
            return false;
        }
        writes.push_back({index, std::move(value).value()});
        return true;
    };

    if (route.tag_index >= 0) {
        const auto input = adapters::mqtt::parse_tag_write(message.payload);
        if (!input) return reject_write(reply, message.topic, input.error());
        if (!add(static_cast<std::size_t>(route.tag_index), input.value())) return;
    } else {
        const auto inputs = adapters::mqtt::parse_exchange_write(message.payload);
        if (!inputs) return reject_write(reply, message.topic, inputs.error());
        for (const auto& [name, input] : inputs.value()) {
            std::size_t index = 0;
            while (index < plan.tags.size() && plan.tags[index].spec.name != name) ++index;
            if (index == plan.tags.size()) {
                return reject(WriteError::unknown_tag,
                              "unknown tag " + name + " in exchange " + route.exchange);
            }
            if (!add(index, input)) return;
        }
    }
    if (auto rejection =
            route.producer->stage(std::move(writes), reply, std::chrono::steady_clock::now())) {
        return reject_write(reply, message.topic, *rejection);
    }
    ++counters_.writes_ok;
}

}  // namespace eip2mqtt::app
