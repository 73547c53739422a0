#pragma once
/// Builds one item of a configuration's `exchanges:` list for integration tests, as
/// DatagramBuilder builds datagrams: the keys a test cares about, named, instead of YAML
/// written by hand in each test.
///
///   start(ExchangeYaml::consume("pump", "10.0.0.2", 7)
///             .length(4).period_ms(1000).topic("area/pump")
///             .tag("SPEED", "0.0", "real")
///             .str());

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace eip2mqtt::test {

class ExchangeYaml {
public:
    /// A consumed exchange; its topic is its name unless topic() says otherwise.
    static ExchangeYaml consume(std::string name, std::string producer_id,
                                std::uint32_t exchange_id);
    /// A produced exchange sent to `destination` (`host:port`).
    static ExchangeYaml produce(std::string name, std::string producer_id,
                                std::uint32_t exchange_id, std::string destination);

    ExchangeYaml& length(std::size_t bytes) { return key("length", std::to_string(bytes)); }
    ExchangeYaml& period_ms(std::uint32_t ms) { return key("period_ms", std::to_string(ms)); }
    ExchangeYaml& timeout_ms(std::uint32_t ms) { return key("timeout_ms", std::to_string(ms)); }
    ExchangeYaml& topic(std::string topic) { return key("topic", std::move(topic)); }
    /// Any other key of the exchange (source, timestamp, clock_tolerance_ms...), as YAML text;
    /// a key given twice keeps its last value.
    ExchangeYaml& key(const std::string& name, std::string value);
    /// One tag; `more` adds keys to its flow mapping (`writable: true, max: 10`).
    ExchangeYaml& tag(const std::string& name, const std::string& address, const std::string& type,
                      const std::string& more = "");

    /// The list item, indented for the `exchanges:` list, ending with a newline.
    std::string str() const;

    /// The produced `cmd` exchange (producer 10.0.0.9, id 9) of one writable dint, SETPOINT
    /// (initially 42), sent every 100 ms to a port nobody reads: the write target of the tests
    /// that need one and care about nothing else in it.
    static std::string setpoint_command();

private:
    ExchangeYaml() = default;

    std::vector<std::pair<std::string, std::string>> keys_;
    std::vector<std::string> tags_;
};

}  // namespace eip2mqtt::test
