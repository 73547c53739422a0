#include "tests/support/exchange_yaml.hpp"

#include <algorithm>

namespace eip2mqtt::test {

ExchangeYaml ExchangeYaml::consume(std::string name, std::string producer_id,
                                   std::uint32_t exchange_id) {
    ExchangeYaml yaml;
    yaml.key("name", name);
    yaml.key("direction", "consume");
    yaml.key("producer_id", std::move(producer_id));
    yaml.key("exchange_id", std::to_string(exchange_id));
    yaml.key("topic", std::move(name));
    return yaml;
}

ExchangeYaml ExchangeYaml::produce(std::string name, std::string producer_id,
                                   std::uint32_t exchange_id, std::string destination) {
    ExchangeYaml yaml;
    yaml.key("name", name);
    yaml.key("direction", "produce");
    yaml.key("producer_id", std::move(producer_id));
    yaml.key("exchange_id", std::to_string(exchange_id));
    yaml.key("destination", std::move(destination));
    yaml.key("topic", std::move(name));
    return yaml;
}

ExchangeYaml& ExchangeYaml::key(const std::string& name, std::string value) {
    const auto it = std::find_if(keys_.begin(), keys_.end(),
                                 [&](const auto& entry) { return entry.first == name; });
    if (it != keys_.end()) {
        it->second = std::move(value);
    } else {
        keys_.emplace_back(name, std::move(value));
    }
    return *this;
}

ExchangeYaml& ExchangeYaml::tag(const std::string& name, const std::string& address,
                                const std::string& type, const std::string& more) {
    auto line = "{ name: " + name + ", address: \"" + address + "\", type: " + type;
    if (!more.empty()) line += ", " + more;
    tags_.push_back(line + " }");
    return *this;
}

std::string ExchangeYaml::str() const {
    std::string out;
    for (const auto& [name, value] : keys_) {
        out += (out.empty() ? "  - " : "    ") + name + ": " + value + "\n";
    }
    if (!tags_.empty()) {
        out += "    tags:\n";
        for (const auto& tag : tags_) out += "      - " + tag + "\n";
    }
    return out;
}

std::string ExchangeYaml::setpoint_command() {
    return produce("cmd", "10.0.0.9", 9, "127.0.0.1:9")
        .length(4)
        .period_ms(100)
        .tag("SETPOINT", "0.0", "dint", "writable: true, initial: 42")
        .str();
}

}  // namespace eip2mqtt::test
