// The gateway, mqtt, eip, metrics and sparkplug sections of the configuration.

#include "adapters/yaml/detail/loader.hpp"

namespace eip2mqtt::adapters::yaml::detail {

void Loader::read_gateway(const Node& node, const Mark& at, Config& config) {
    auto& gateway = config.gateway;
    gateway.marks = walk(node, at, "gateway", "in gateway", gateway_keys,
                         [&](const std::string& key, const Node& value, const Mark& k) {
                             auto& defaults = gateway.exchange_defaults;
                             if (key == "timestamp") {
                                 if (const auto source = timestamp_source(value, key, k)) {
                                     defaults.timestamp = *source;
                                 }
                                 return;
                             }
                             if (key == "clock_tolerance_ms") {
                                 if (const auto n = integer<long long>(value, key, k, 0)) {
                                     defaults.clock_tolerance = std::chrono::milliseconds(*n);
                                 }
                                 return;
                             }
                             const auto s = text(value, key, k);
                             if (!s) return;
                             if (key == "id") gateway.id = *s;
                             if (key == "state_dir") gateway.state_dir = *s;
                             if (key == "log_level") gateway.log_level = lower(*s);
                         });
}

void Loader::read_mqtt(const Node& node, const Mark& at, Config& config) {
    auto& mqtt = config.mqtt;
    mqtt.marks =
        walk(node, at, "mqtt", "in mqtt", mqtt_keys,
             [&](const std::string& key, const Node& value, const Mark& k) {
                 if (key == "url" || key == "client_id" || key == "username" ||
                     key == "password_file" || key == "base_topic") {
                     const auto s = text(value, key, k);
                     if (!s) return;
                     if (key == "url") mqtt.url = *s;
                     if (key == "client_id") mqtt.client_id = *s;
                     if (key == "username") mqtt.username = *s;
                     if (key == "password_file") mqtt.password_file = *s;
                     if (key == "base_topic") mqtt.base_topic = *s;
                 } else if (key == "version") {
                     const std::string v(value.scalar());
                     if (v == "3.1.1") {
                         mqtt.version = 3;
                     } else if (const auto n = parse_integer<int>(v)) {
                         mqtt.version = *n;  // validate() accepts 5 and 3
                     } else {
                         error(k, "mqtt version must be 5 or 3.1.1");
                     }
                 } else if (key == "qos") {
                     if (const auto n = integer<int>(value, key, k)) mqtt.qos = *n;
                 } else if (key == "retain") {
                     if (const auto b = boolean(value, key, k)) mqtt.retain = *b;
                 } else if (key == "batch") {
                     if (const auto b = boolean(value, key, k)) mqtt.batch = *b;
                 } else if (key == "batch_first") {
                     if (const auto b = boolean(value, key, k)) mqtt.batch_first = *b;
                 } else if (key == "allow_response_topics_under_base") {
                     if (const auto b = boolean(value, key, k)) {
                         mqtt.allow_response_topics_under_base = *b;
                     }
                 } else if (key == "payload") {
                     const auto s = text(value, key, k);
                     if (s && *s == "json") {
                         mqtt.payload = core::config::PayloadFormat::json;
                     } else if (s && *s == "raw") {
                         mqtt.payload = core::config::PayloadFormat::raw;
                     } else if (s) {
                         error(k, "payload " + in_quotes(*s) + " is not json or raw");
                     }
                 } else if (key == "keepalive_s") {
                     if (const auto n = integer<int>(value, key, k, 1, 65535)) {
                         mqtt.keepalive = std::chrono::seconds(*n);
                     }
                 } else if (key == "session_expiry_s") {
                     if (const auto n = integer<long long>(value, key, k, 0, 4294967295LL)) {
                         mqtt.session_expiry = std::chrono::seconds(*n);
                     }
                 } else if (key == "metrics_interval_s") {
                     if (const auto n = integer<int>(value, key, k, 1, 86400)) {
                         mqtt.metrics_interval = std::chrono::seconds(*n);
                     }
                 } else if (key == "store_and_forward") {
                     read_store_and_forward(value, k, config);
                 } else if (key == "buffer") {
                     walk(value, k, "buffer", "in mqtt.buffer", buffer_keys,
                          [&](const std::string& key2, const Node& v2, const Mark& k2) {
                              if (const auto n = integer<std::size_t>(v2, key2, k2, 1)) {
                                  mqtt.buffer_max_messages = *n;
                              }
                          });
                 } else if (key == "tls") {
                     core::config::TlsSection tls;
                     walk(value, k, "tls", "in mqtt.tls", tls_keys,
                          [&](const std::string& key2, const Node& v2, const Mark& k2) {
                              if (key2 == "verify") {
                                  if (const auto b = boolean(v2, key2, k2)) tls.verify = *b;
                                  return;
                              }
                              const auto s = text(v2, key2, k2);
                              if (!s) return;
                              if (key2 == "ca_file") tls.ca_file = *s;
                              if (key2 == "cert_file") tls.cert_file = *s;
                              if (key2 == "key_file") tls.key_file = *s;
                          });
                     if (!value.is_null()) mqtt.tls = tls;
                 }
             });
}

void Loader::read_store_and_forward(const Node& node, const Mark& at, Config& config) {
    auto& section = config.mqtt.store_and_forward;
    section.marks =
        walk(node, at, "store_and_forward", "in mqtt.store_and_forward", store_and_forward_keys,
             [&](const std::string& key, const Node& value, const Mark& k) {
                 if (key == "enabled") {
                     if (const auto b = boolean(value, key, k)) section.enabled = *b;
                 } else if (key == "max_mb") {
                     // A journal smaller than a megabyte would drop history at once.
                     if (const auto n = integer<std::uint64_t>(value, key, k, 1, 1ull << 30)) {
                         section.max_mb = *n;
                     }
                 } else if (key == "replay_rate") {
                     if (const auto n = integer<std::uint32_t>(value, key, k, 1, 1000000)) {
                         section.replay_rate = *n;
                     }
                 } else if (key == "fsync_interval_ms") {
                     if (const auto n = integer<std::uint32_t>(value, key, k, 10, 3600000)) {
                         section.fsync_interval = std::chrono::milliseconds(*n);
                     }
                 }
             });
}

void Loader::read_eip(const Node& node, const Mark& at, Config& config) {
    auto& eip = config.eip;
    eip.marks = walk(
        node, at, "eip", "in eip", eip_keys,
        [&](const std::string& key, const Node& value, const Mark& k) {
            if (key == "bind") {
                const auto s = text(value, key, k);
                if (s && !parse_ipv4(*s)) {
                    error(k, "bind " + in_quotes(*s) + " is not an IPv4 address");
                } else if (s) {
                    eip.bind = *s;
                }
            } else if (key == "port") {
                if (const auto n = integer<std::uint16_t>(value, key, k)) eip.port = *n;
            } else if (key == "multicast_ttl") {
                if (const auto n = integer<int>(value, key, k, 0, 255)) eip.multicast_ttl = *n;
            } else if (key == "multicast_interface") {
                const auto s = text(value, key, k);
                if (s && !parse_ipv4(*s)) {
                    error(k, "multicast_interface " + in_quotes(*s) + " is not an IPv4 address");
                } else if (s) {
                    eip.multicast_interface = *s;
                }
            } else if (key == "commands") {
                read_commands(value, k, config);
            } else if (key == "multicast") {
                if (value.is_null()) return;
                if (!value.is_sequence()) {
                    error(k, "expected a list for 'multicast'");
                    return;
                }
                for (std::size_t i = 0; i < value.size(); ++i) {
                    const Node item = value.item(i);
                    core::config::MulticastGroup group;
                    const auto item_marks =
                        walk(item, mark(item), "multicast", "in a multicast entry", multicast_keys,
                             [&](const std::string& key2, const Node& v2, const Mark& k2) {
                                 const auto s = text(v2, key2, k2);
                                 if (!s) return;
                                 if (key2 == "interface") group.interface = *s;
                                 if (key2 != "group") return;
                                 group.group = *s;
                                 const auto ip = parse_ipv4(*s);
                                 if (!ip || (*ip >> 28) != 0xE) {
                                     error(k2, "multicast group " + in_quotes(*s) +
                                                   " is not an IPv4 multicast address "
                                                   "(224.0.0.0-239.255.255.255)");
                                 }
                             });
                    if (!item_marks.contains("group")) {
                        error(item_marks.node, "multicast entry lacks 'group'");
                    }
                    eip.multicast.push_back(std::move(group));
                }
            }
        });
}

void Loader::read_commands(const Node& node, const Mark& at, Config& config) {
    auto& commands = config.eip.commands;
    commands.marks =
        walk(node, at, "commands", "in eip.commands", commands_keys,
             [&](const std::string& key, const Node& value, const Mark& k) {
                 if (key == "enabled") {
                     if (const auto b = boolean(value, key, k)) commands.enabled = *b;
                 } else if (key == "writes") {
                     if (const auto b = boolean(value, key, k)) commands.writes = *b;
                 } else if (key == "port") {
                     if (const auto n = integer<std::uint16_t>(value, key, k, 1))
                         commands.port = *n;
                 } else if (key == "max_requests_per_s") {
                     if (const auto n = integer<std::uint32_t>(value, key, k, 1, 100000)) {
                         commands.max_requests_per_s = *n;
                     }
                 } else if (key == "allow") {
                     if (!value.is_sequence()) {
                         error(k, "expected a list of subnets for 'allow' (10.20.0.0/24)");
                         return;
                     }
                     for (std::size_t i = 0; i < value.size(); ++i) {
                         const Node item = value.item(i);
                         const auto s = text(item, key, mark(item));
                         if (!s) continue;
                         if (const auto subnet = core::command::parse_subnet(*s)) {
                             commands.allow.push_back(*subnet);
                         } else {
                             error(mark(item), "allow " + in_quotes(*s) +
                                                   " is not an IPv4 subnet (10.20.0.0/24)");
                         }
                     }
                 }
             });
}

void Loader::read_metrics(const Node& node, const Mark& at, Config& config) {
    config.metrics.marks = walk(node, at, "metrics", "in metrics", metrics_keys,
                                [&](const std::string& key, const Node& value, const Mark& k) {
                                    const auto s = text(value, key, k);
                                    if (!s || s->empty()) return;
                                    if (!valid_host_port(*s, true)) {
                                        error(k, "listen " + in_quotes(*s) + " is not host:port");
                                        return;
                                    }
                                    config.metrics.listen = *s;
                                });
}

void Loader::read_sparkplug(const Node& node, const Mark& at, Config& config) {
    auto& sparkplug = config.sparkplug;
    sparkplug.marks =
        walk(node, at, "sparkplug", "in sparkplug", sparkplug_keys,
             [&](const std::string& key, const Node& value, const Mark& k) {
                 if (key == "uns") {
                     if (const auto b = boolean(value, key, k)) sparkplug.uns = *b;
                 } else if (key == "qos") {
                     if (const auto n = integer<int>(value, key, k, 0, 1)) sparkplug.qos = *n;
                 } else if (key == "max_packet_bytes") {
                     // MQTT's own limit is 268,435,460 bytes; 0: none of ours.
                     if (const auto n = integer<long long>(value, key, k, 0, 268435460LL))
                         sparkplug.max_packet_bytes = static_cast<std::size_t>(*n);
                 } else if (const auto s = text(value, key, k)) {
                     if (key == "group_id") sparkplug.group_id = *s;
                     if (key == "edge_node_id") sparkplug.edge_node_id = *s;
                     if (key == "primary_host_id") sparkplug.primary_host_id = *s;
                 }
             });
    if (!node.is_null() && node.is_defined() && sparkplug.group_id.empty() &&
        !sparkplug.marks.contains("group_id")) {
        error(sparkplug.marks.node, "sparkplug lacks 'group_id' (required to enable Sparkplug B)");
    }
}

}  // namespace eip2mqtt::adapters::yaml::detail
