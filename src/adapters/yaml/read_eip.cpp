// The eip section of the configuration: the UDP endpoint, its multicast groups and the
// command port.

#include "adapters/yaml/detail/sections.hpp"

namespace eip2mqtt::adapters::yaml::detail {
namespace {

constexpr auto eip_keys = core::config::keys::names(core::config::keys::eip);
constexpr auto multicast_keys = core::config::keys::names(core::config::keys::multicast);
constexpr auto commands_keys = core::config::keys::names(core::config::keys::commands);

/// The text itself when it is an IPv4 address: an address is kept as written, for the socket.
std::optional<std::string> ipv4_text(std::string_view text) {
    if (!parse_ipv4(text)) return std::nullopt;
    return std::string(text);
}

void read_multicast(Reader& reader, const Node& value, const Mark& k,
                    core::config::EipSection& eip) {
    if (value.is_null()) return;
    if (!value.is_sequence()) {
        reader.error(k, "expected a list for 'multicast'");
        return;
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
        const Node item = value.item(i);
        core::config::MulticastGroup group;
        const auto item_marks =
            reader.walk(item, reader.mark(item), "multicast", "in a multicast entry",
                        multicast_keys, [&](const std::string& key, const Node& v, const Mark& at) {
                            const auto s = reader.text(v, key, at);
                            if (!s) return;
                            if (key == "interface") group.interface = *s;
                            if (key != "group") return;
                            group.group = *s;
                            const auto ip = parse_ipv4(*s);
                            if (!ip || (*ip >> 28) != 0xE) {
                                reader.error(at, "multicast group " + in_quotes(*s) +
                                                     " is not an IPv4 multicast address "
                                                     "(224.0.0.0-239.255.255.255)");
                            }
                        });
        if (!item_marks.contains("group")) {
            reader.error(item_marks.node, "multicast entry lacks 'group'");
        }
        eip.multicast.push_back(std::move(group));
    }
}

/// A list of IPv4 subnets (`eip.commands.allow`, `trusted`); each bad item an error.
std::vector<core::net::Subnet> subnets(Reader& reader, const Node& value, const std::string& key,
                                       const Mark& at) {
    std::vector<core::net::Subnet> out;
    if (!value.is_sequence()) {
        reader.error(at, "expected a list of subnets for " + in_quotes(key) + " (10.20.0.0/24)");
        return out;
    }
    for (std::size_t i = 0; i < value.size(); ++i) {
        const Node item = value.item(i);
        const auto s = reader.text(item, key, reader.mark(item));
        if (!s) continue;
        if (const auto subnet = core::net::parse_subnet(*s)) {
            out.push_back(*subnet);
        } else {
            reader.error(reader.mark(item),
                         key + " " + in_quotes(*s) + " is not an IPv4 subnet (10.20.0.0/24)");
        }
    }
    return out;
}

void read_commands(Reader& reader, const Node& node, const Mark& at, Config& config) {
    auto& commands = config.eip.commands;
    commands.marks = reader.walk(
        node, at, "commands", "in eip.commands", commands_keys,
        [&](const std::string& key, const Node& value, const Mark& k) {
            if (key == "enabled") {
                if (const auto b = reader.boolean(value, key, k)) commands.enabled = *b;
            } else if (key == "writes") {
                if (const auto b = reader.boolean(value, key, k)) commands.writes = *b;
            } else if (key == "port") {
                if (const auto n = reader.integer<std::uint16_t>(value, key, k, 1))
                    commands.port = *n;
            } else if (key == "max_requests_per_s") {
                if (const auto n = reader.integer<std::uint32_t>(value, key, k, 1, 100000)) {
                    commands.max_requests_per_s = *n;
                }
            } else if (key == "max_requests_per_s_per_source") {
                if (const auto n = reader.integer<std::uint32_t>(value, key, k, 1, 100000)) {
                    commands.max_requests_per_s_per_source = *n;
                }
            } else if (key == "allow") {
                commands.allow = subnets(reader, value, key, k);
            } else if (key == "trusted") {
                commands.trusted = subnets(reader, value, key, k);
            }
        });
}

}  // namespace

void read_eip(Reader& reader, const Node& node, const Mark& at, Config& config) {
    auto& eip = config.eip;
    eip.marks = reader.walk(
        node, at, "eip", "in eip", eip_keys,
        [&](const std::string& key, const Node& value, const Mark& k) {
            if (key == "bind") {
                if (auto s = reader.parsed(value, key, k, ipv4_text, "is not an IPv4 address")) {
                    eip.bind = std::move(*s);
                }
            } else if (key == "port") {
                if (const auto n = reader.integer<std::uint16_t>(value, key, k)) eip.port = *n;
            } else if (key == "multicast_ttl") {
                if (const auto n = reader.integer<int>(value, key, k, 0, 255))
                    eip.multicast_ttl = *n;
            } else if (key == "multicast_interface") {
                if (auto s = reader.parsed(value, key, k, ipv4_text, "is not an IPv4 address")) {
                    eip.multicast_interface = std::move(*s);
                }
            } else if (key == "link_mbps") {
                const auto mbps = reader.number(value, key, k);
                if (mbps && !(*mbps > 0 && *mbps <= core::config::max_link_mbps)) {
                    reader.error(k,
                                 "link_mbps must be more than 0 and at most " +
                                     std::to_string(static_cast<int>(core::config::max_link_mbps)));
                } else if (mbps) {
                    eip.link_mbps = *mbps;
                }
            } else if (key == "commands") {
                read_commands(reader, value, k, config);
            } else if (key == "multicast") {
                read_multicast(reader, value, k, eip);
            }
        });
}

}  // namespace eip2mqtt::adapters::yaml::detail
