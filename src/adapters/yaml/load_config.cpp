#include "eip2mqtt/adapters/yaml/load_config.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <yaml-cpp/exceptions.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "adapters/yaml/detail/syntax_cache.hpp"
#include "adapters/yaml/detail/tree.hpp"
#include "eip2mqtt/core/config/point_index.hpp"
#include "eip2mqtt/core/config/point_list.hpp"
#include "eip2mqtt/core/plan/address.hpp"
#include "eip2mqtt/core/plan/tag_type.hpp"
#include "eip2mqtt/core/wire/header.hpp"

namespace eip2mqtt::adapters::yaml {
namespace {

/// What a file that is not a regular one is, for a message: "a directory".
std::string_view kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "of an unknown kind";
}

/// The whole of a regular file of at most max_file_bytes, or why not, with `what` naming it
/// ("point list 'x.csv'"). Opened without blocking (a FIFO without a writer would block the
/// open for ever), checked on the opened descriptor (what is read is what was checked), and
/// never read past the limit, whatever its size said (a file may grow meanwhile; /proc files
/// say 0). Read as a stream, a directory ended in std::bad_alloc, a FIFO blocked and
/// /dev/zero grew the memory without end.
core::Result<std::string, std::string> read_file(const std::string& path, const std::string& what) {
    const auto cannot = [&](int error) {
        return core::fail("cannot read " + what + ": " + std::strerror(error));
    };
    const auto too_big = [&](const std::string& size) {
        return core::fail(what + " is " + size + " bytes; the limit is " +
                          std::to_string(max_file_bytes) + " (" +
                          std::to_string(max_file_bytes >> 20) + " MiB)");
    };
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return cannot(errno);
    const struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat status = {};
    if (::fstat(fd, &status) != 0) return cannot(errno);
    if (!S_ISREG(status.st_mode)) {
        return core::fail(what + " is not a regular file (" + std::string(kind_of(status.st_mode)) +
                          ")");
    }
    if (static_cast<std::uintmax_t>(status.st_size) > max_file_bytes) {
        return too_big(std::to_string(status.st_size));
    }
    // Sized for one read (a 5 MB file once went through an ostringstream and was copied out
    // of it again), and one byte more, to see the end without growing.
    std::string text(static_cast<std::size_t>(status.st_size) + 1, '\0');
    std::size_t filled = 0;
    while (true) {
        if (filled == text.size()) {
            if (filled > max_file_bytes) {
                return too_big("more than " + std::to_string(max_file_bytes));
            }
            text.resize(std::min(std::max<std::size_t>(2 * filled, 4096), max_file_bytes + 1));
        }
        const auto n = ::read(fd, text.data() + filled, text.size() - filled);
        if (n < 0) {
            if (errno == EINTR) continue;
            return cannot(errno);
        }
        if (n == 0) break;
        filled += static_cast<std::size_t>(n);
    }
    text.resize(filled);
    return text;
}

using core::config::Config;
using core::config::Diagnostic;
using core::config::Diagnostics;
using core::config::ExchangeConfig;
using core::config::FileName;
using core::config::in_quotes;
using core::config::Mark;
using core::config::Marks;
using core::config::TagConfig;
using core::plan::Direction;
using core::plan::TagType;
using detail::Node;

using Keys = std::span<const std::string_view>;

constexpr std::array<std::string_view, 5> top_keys{"gateway", "mqtt", "eip", "metrics",
                                                   "exchanges"};
constexpr std::array<std::string_view, 5> gateway_keys{"id", "state_dir", "log_level", "timestamp",
                                                       "clock_tolerance_ms"};
constexpr std::array<std::string_view, 16> mqtt_keys{"url",
                                                     "version",
                                                     "client_id",
                                                     "username",
                                                     "password_file",
                                                     "tls",
                                                     "base_topic",
                                                     "qos",
                                                     "retain",
                                                     "payload",
                                                     "buffer",
                                                     "batch",
                                                     "keepalive_s",
                                                     "metrics_interval_s",
                                                     "session_expiry_s",
                                                     "allow_response_topics_under_base"};
constexpr std::array<std::string_view, 4> tls_keys{"ca_file", "cert_file", "key_file", "verify"};
constexpr std::array<std::string_view, 1> buffer_keys{"max_messages"};
constexpr std::array<std::string_view, 5> eip_keys{"bind", "port", "multicast", "multicast_ttl",
                                                   "multicast_interface"};
constexpr std::array<std::string_view, 2> multicast_keys{"group", "interface"};
constexpr std::array<std::string_view, 1> metrics_keys{"listen"};
constexpr std::array<std::string_view, 15> exchange_keys{
    "name",      "direction",   "producer_id", "exchange_id", "length",
    "signature", "period_ms",   "timeout_ms",  "timestamp",   "clock_tolerance_ms",
    "source",    "destination", "topic",       "points",      "tags"};
constexpr std::array<std::string_view, 12> tag_keys{
    "name",     "address", "type", "unit",    "deadband",    "refresh_s",
    "writable", "min",     "max",  "initial", "description", "max_writes_per_s"};

std::string lower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return out;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] =
                std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
            diagonal = above;
        }
    }
    return row[b.size()];
}

/// The allowed key closest to `key`, when it is close enough to be a typo.
std::optional<std::string_view> suggestion(std::string_view key, Keys allowed) {
    std::optional<std::string_view> best;
    std::size_t best_distance = 3;  // at most 2 edits
    const std::string key_lower = lower(key);
    for (const auto candidate : allowed) {
        const auto distance = edit_distance(key_lower, candidate);
        if (distance < best_distance && distance < candidate.size()) {
            best = candidate;
            best_distance = distance;
        }
    }
    return best;
}

template <class T>
std::optional<T> parse_integer(std::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    T value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty()) return std::nullopt;
    return value;
}

std::optional<double> parse_double(std::string_view text) {
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc{} || end != text.data() + text.size() || text.empty() ||
        !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

/// A dotted IPv4 address, host order.
std::optional<std::uint32_t> parse_ipv4(std::string_view text) {
    if (std::count(text.begin(), text.end(), '.') != 3) return std::nullopt;
    const auto id = core::wire::parse_producer_id(text);
    if (!id) return std::nullopt;
    return id->value;
}

/// `host` or `host:port`: the port, when written, must be 1..65535.
bool valid_host_port(std::string_view text, bool port_required) {
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos) return !port_required && !text.empty();
    const auto port = parse_integer<unsigned>(text.substr(colon + 1));
    return colon > 0 && port && *port >= 1 && *port <= 65535;
}

class Loader {
public:
    explicit Loader(std::string file, std::filesystem::path syntax_cache_dir = {})
        : file_(std::move(file)),
          dir_(std::filesystem::path(file_.str()).parent_path()),
          syntax_cache_dir_(std::move(syntax_cache_dir)) {}

    core::Result<Config, Diagnostics> load(const std::string& text) {
        Config config;
        config.file = file_;
        try {
            const detail::Tree tree =
                detail::parse_with_cache(text, file_.str(), syntax_cache_dir_);
            const Node root = tree.root();
            if (!root.is_defined() || root.is_null()) {
                error({file_, 1, 1}, "the configuration is empty");
                return core::fail(std::move(diagnostics_));
            }
            if (!root.is_map()) {
                error(mark(root), "expected a mapping at the top level");
            } else {
                read_root(root, config);
            }
        } catch (const YAML::Exception& e) {
            error(mark(e.mark), "YAML syntax error: " + e.msg);
            return core::fail(std::move(diagnostics_));
        }
        if (config.mqtt.client_id.empty()) config.mqtt.client_id = "eip2mqtt-" + config.gateway.id;
        // Semantic checks also run after local errors so that one run shows every problem;
        // entities whose own keys failed to parse were left out of the model to avoid echoes.
        auto semantic = core::config::validate(config);
        diagnostics_.insert(diagnostics_.end(), std::make_move_iterator(semantic.begin()),
                            std::make_move_iterator(semantic.end()));
        if (diagnostics_.empty()) return config;
        std::stable_sort(diagnostics_.begin(), diagnostics_.end(),
                         [this](const Diagnostic& a, const Diagnostic& b) {
                             return std::make_tuple(a.mark.file != file_, a.mark.file, a.mark.line,
                                                    a.mark.column) <
                                    std::make_tuple(b.mark.file != file_, b.mark.file, b.mark.line,
                                                    b.mark.column);
                         });
        return core::fail(std::move(diagnostics_));
    }

private:
    Mark mark(const YAML::Mark& m) const {
        if (m.is_null()) return {file_, 0, 0};
        return {file_, m.line + 1, m.column + 1};
    }
    Mark mark(const Node& node) const { return mark(node.mark()); }

    void error(const Mark& at, std::string message) {
        diagnostics_.push_back({at, std::move(message)});
    }

    /// Walks a mapping: reports unknown and repeated keys, records every key's mark, and hands
    /// each known key to `handle(key, value, mark)`. `where` completes "unknown key 'x' in ...":
    /// a string, or a callable that makes it only for a message (a tag's, built for each of
    /// 100,000 tags, cost two heap strings a tag for errors that mostly never come). Templates,
    /// not std::function: a handler capturing a tag's state would be a heap block per tag too.
    template <class Where, class Handle>
    Marks walk(const Node& node, const Mark& at, const std::string& what, const Where& where,
               Keys allowed, const Handle& handle) {
        const auto where_text = [&]() -> std::string {
            if constexpr (std::is_invocable_v<const Where&>) {
                return where();
            } else {
                return where;
            }
        };
        Marks marks;
        marks.node = node.is_defined() && !node.is_null() ? mark(node) : at;
        if (!node.is_defined() || node.is_null()) return marks;
        if (!node.is_map()) {
            error(at, "expected a mapping for " + in_quotes(what));
            return marks;
        }
        marks.keys.reserve(node.size());
        for (std::size_t i = 0; i < node.size(); ++i) {
            const Node key_node = node.key(i);
            const Mark key_mark = mark(key_node);
            if (!key_node.is_scalar()) {
                error(key_mark, "expected a plain key " + where_text());
                continue;
            }
            const std::string key(key_node.scalar());
            if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
                std::string message = "unknown key " + in_quotes(key) + " " + where_text();
                if (const auto close = suggestion(key, allowed)) {
                    message += " (did you mean " + in_quotes(*close) + "?)";
                }
                error(key_mark, std::move(message));
                continue;
            }
            if (!marks.add(key, key_mark)) {
                error(key_mark, "duplicate key " + in_quotes(key) + " " + where_text());
                continue;
            }
            handle(key, node.value(i), key_mark);
        }
        return marks;
    }

    // --- scalars ------------------------------------------------------------------------------

    /// A string value read by `parse` (returning an optional); one that does not parse is
    /// reported as "<key> '<text>' <problem>" (text() reports a value that is no string).
    template <class Parse>
    auto parsed(const Node& value, const std::string& key, const Mark& at, Parse parse,
                std::string_view problem) -> decltype(parse(std::string_view())) {
        const auto s = text(value, key, at);
        if (!s) return std::nullopt;
        auto result = parse(*s);
        if (!result) error(at, key + " " + in_quotes(*s) + " " + std::string(problem));
        return result;
    }

    std::optional<std::string> text(const Node& value, const std::string& key, const Mark& at) {
        if (value.is_null()) return std::string();
        if (!value.is_scalar()) {
            error(at, "expected a string for " + in_quotes(key));
            return std::nullopt;
        }
        return std::string(value.scalar());
    }

    template <class T>
    std::optional<T> integer(const Node& value, const std::string& key, const Mark& at,
                             T min = std::numeric_limits<T>::min(),
                             T max = std::numeric_limits<T>::max()) {
        const auto parsed =
            value.is_scalar() ? parse_integer<long long>(value.scalar()) : std::nullopt;
        if (!parsed) {
            error(at, "expected an integer for " + in_quotes(key));
            return std::nullopt;
        }
        if (*parsed < static_cast<long long>(min) ||
            (*parsed > 0 &&
             static_cast<unsigned long long>(*parsed) > static_cast<unsigned long long>(max))) {
            error(at, in_quotes(key) + " " + std::to_string(*parsed) + " is outside " +
                          std::to_string(min) + ".." + std::to_string(max));
            return std::nullopt;
        }
        return static_cast<T>(*parsed);
    }

    std::optional<core::plan::TimestampSource> timestamp_source(const Node& value,
                                                                const std::string& key,
                                                                const Mark& at) {
        return parsed(value, key, at, core::plan::parse_timestamp_source,
                      "is not one of auto, producer, receive");
    }

    std::optional<double> number(const Node& value, const std::string& key, const Mark& at) {
        const auto parsed = value.is_scalar() ? parse_double(value.scalar()) : std::nullopt;
        if (!parsed) error(at, "expected a number for " + in_quotes(key));
        return parsed;
    }

    std::optional<bool> boolean(const Node& value, const std::string& key, const Mark& at) {
        if (value.is_scalar()) {
            const auto word = lower(value.scalar());
            if (word == "true" || word == "yes" || word == "on") return true;
            if (word == "false" || word == "no" || word == "off") return false;
        }
        error(at, "expected true or false for " + in_quotes(key));
        return std::nullopt;
    }

    // --- sections -----------------------------------------------------------------------------

    void read_root(const Node& root, Config& config) {
        walk(root, mark(root), "configuration", "at the top level", top_keys,
             [&](const std::string& key, const Node& value, const Mark& at) {
                 if (key == "gateway") read_gateway(value, at, config);
                 if (key == "mqtt") read_mqtt(value, at, config);
                 if (key == "eip") read_eip(value, at, config);
                 if (key == "metrics") read_metrics(value, at, config);
                 if (key == "exchanges") read_exchanges(value, at, config);
             });
    }

    void read_gateway(const Node& node, const Mark& at, Config& config) {
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

    void read_mqtt(const Node& node, const Mark& at, Config& config) {
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

    void read_eip(const Node& node, const Mark& at, Config& config) {
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
                        error(k,
                              "multicast_interface " + in_quotes(*s) + " is not an IPv4 address");
                    } else if (s) {
                        eip.multicast_interface = *s;
                    }
                } else if (key == "multicast") {
                    if (value.is_null()) return;
                    if (!value.is_sequence()) {
                        error(k, "expected a list for 'multicast'");
                        return;
                    }
                    for (std::size_t i = 0; i < value.size(); ++i) {
                        const Node item = value.item(i);
                        core::config::MulticastGroup group;
                        const auto item_marks = walk(
                            item, mark(item), "multicast", "in a multicast entry", multicast_keys,
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

    void read_metrics(const Node& node, const Mark& at, Config& config) {
        config.metrics.marks =
            walk(node, at, "metrics", "in metrics", metrics_keys,
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

    void read_exchanges(const Node& node, const Mark& at, Config& config) {
        if (node.is_null()) return;
        if (!node.is_sequence()) {
            error(at, "expected a list for 'exchanges'");
            return;
        }
        int index = 0;
        for (std::size_t i = 0; i < node.size(); ++i) {
            const Node item = node.item(i);
            ++index;
            read_exchange(item, index, config);
        }
    }

    void read_exchange(const Node& node, int index, Config& config) {
        ExchangeConfig exchange;
        auto& spec = exchange.spec;
        bool broken = false;  // an identity key is missing or bad: leave it out of the model
        std::string label = "exchange #" + std::to_string(index);
        if (const Node name = node.find("name"); name.is_scalar()) {
            label = "exchange " + in_quotes(name.scalar());
        }
        const std::string where = "in " + label;
        std::optional<Node> tags_node;
        std::string points;
        bool topic_written = false;

        exchange.marks = walk(
            node, mark(node), label, where, exchange_keys,
            [&](const std::string& key, const Node& value, const Mark& k) {
                if (key == "name") {
                    if (const auto s = text(value, key, k)) {
                        spec.name = *s;
                    } else {
                        broken = true;
                    }
                } else if (key == "direction") {
                    const auto s = text(value, key, k);
                    if (s && *s == "consume") {
                        spec.direction = Direction::consume;
                    } else if (s && *s == "produce") {
                        spec.direction = Direction::produce;
                    } else {
                        if (s)
                            error(k, "direction " + in_quotes(*s) + " is not consume or produce");
                        broken = true;
                    }
                } else if (key == "producer_id") {
                    if (const auto id =
                            parsed(value, key, k, core::wire::parse_producer_id,
                                   "is not a.b.c.d or a plain integer (GE decimal form)")) {
                        spec.producer_id = *id;
                    } else {
                        broken = true;
                    }
                } else if (key == "exchange_id") {
                    if (const auto n = integer<std::uint32_t>(value, key, k)) {
                        spec.exchange_id = *n;
                    } else {
                        broken = true;
                    }
                } else if (key == "length") {
                    if (const auto n = integer<long long>(value, key, k)) {
                        if (*n < 0 || *n > std::numeric_limits<std::uint16_t>::max()) {
                            error(k,
                                  label + " length " + std::to_string(*n) + " is outside 1..1400");
                        } else {
                            spec.length = static_cast<std::uint16_t>(*n);
                        }
                    }
                } else if (key == "signature") {
                    if (const auto sig = parsed(value, key, k, core::wire::parse_signature,
                                                "is not major.minor (each 0..255)")) {
                        spec.signature = *sig;
                    }
                } else if (key == "period_ms") {
                    if (const auto n = integer<long long>(value, key, k)) {
                        spec.period = std::chrono::milliseconds(*n);
                    }
                } else if (key == "timeout_ms") {
                    if (const auto n = integer<long long>(value, key, k, 0)) {
                        spec.timeout = std::chrono::milliseconds(*n);
                    }
                } else if (key == "timestamp") {
                    spec.timestamp = timestamp_source(value, key, k);
                } else if (key == "clock_tolerance_ms") {
                    if (const auto n = integer<long long>(value, key, k, 0)) {
                        spec.clock_tolerance = std::chrono::milliseconds(*n);
                    }
                } else if (key == "source") {
                    if (const auto ip =
                            parsed(value, key, k, parse_ipv4, "is not an IPv4 address")) {
                        spec.source = *ip;
                    }
                } else if (key == "destination") {
                    const auto s = text(value, key, k);
                    if (s && !s->empty() && !valid_host_port(*s, false)) {
                        error(k, "destination " + in_quotes(*s) +
                                     " is not host or host:port (port 1..65535)");
                    } else if (s) {
                        spec.destination = *s;
                    }
                } else if (key == "topic") {
                    if (const auto s = text(value, key, k)) spec.topic = *s;
                    topic_written = true;
                } else if (key == "points") {
                    if (const auto s = text(value, key, k)) points = *s;
                } else if (key == "tags") {
                    tags_node.emplace(value);
                }
            });
        if (!node.is_map()) return;
        for (const std::string_view required : {"name", "producer_id", "exchange_id"}) {
            if (!exchange.marks.contains(required)) {
                error(exchange.marks.node, label + " lacks " + in_quotes(required));
                broken = true;
            }
        }
        if (!topic_written) spec.topic = spec.name;
        spec.points = points;

        if (tags_node && !tags_node->is_null()) {
            if (!tags_node->is_sequence()) {
                error(exchange.marks.of("tags"), "expected a list for 'tags'");
            } else {
                // Sized once: vectors doubling per tag left freed blocks of every size among
                // the tags, where the long-lived plans then landed (1,000 x 100 tags: RSS
                // 29.5 MB idle, 25.2 MB sized once).
                exchange.tags.reserve(tags_node->size());
                for (std::size_t i = 0; i < tags_node->size(); ++i) {
                    const Node item = tags_node->item(i);
                    if (auto tag = read_tag(item, label)) exchange.tags.push_back(std::move(*tag));
                }
            }
        }
        if (!points.empty()) read_points(points, exchange);
        if (!broken) config.exchanges.push_back(std::move(exchange));
    }

    std::optional<TagConfig> read_tag(const Node& node, const std::string& exchange_label) {
        TagConfig tag;
        auto& spec = tag.spec;
        bool broken = false;  // a value failed to parse: leave the tag out of the model
        const auto label = [&] {
            const Node name = node.find("name");
            return (name.is_scalar() ? "tag " + in_quotes(name.scalar()) : std::string("a tag")) +
                   " of " + exchange_label;
        };
        std::optional<Node> initial;
        Mark initial_mark;
        tag.marks = walk(
            node, mark(node), "tag", [&] { return "in " + label(); }, tag_keys,
            [&](const std::string& key, const Node& value, const Mark& k) {
                if (key == "name" || key == "unit" || key == "description") {
                    const auto s = text(value, key, k);
                    if (!s) {
                        broken = true;
                    } else if (key == "name") {
                        spec.name = *s;
                    } else if (key == "unit") {
                        spec.mutable_extras().unit = *s;
                    }
                } else if (key == "address") {
                    // `126.0` unquoted is a YAML float: its scalar text is what was written.
                    if (const auto address = parsed(value, key, k, core::plan::parse_address,
                                                    "is not byte.bit (byte 0..65535, bit 0..7)")) {
                        spec.address = *address;
                    } else {
                        broken = true;
                    }
                } else if (key == "type") {
                    const auto s = text(value, key, k);
                    const auto type =
                        s ? core::plan::parse_tag_type(*s, core::plan::TypeNaming::yaml)
                          : std::nullopt;
                    if (type) {
                        spec.type = *type;
                    } else {
                        if (s) {
                            error(k, "unknown type " + in_quotes(*s) +
                                         " (expected bit, byte, int, word, dint, udint, real, "
                                         "lint or lreal)");
                        }
                        broken = true;
                    }
                } else if (key == "deadband") {
                    if (const auto d = number(value, key, k)) {
                        spec.deadband = *d;
                    } else {
                        broken = true;
                    }
                } else if (key == "refresh_s") {
                    if (const auto n = integer<long long>(value, key, k, 0)) {
                        spec.refresh = std::chrono::seconds(*n);
                    } else {
                        broken = true;
                    }
                } else if (key == "max_writes_per_s") {
                    if (const auto d = number(value, key, k); d && *d >= 0) {
                        spec.mutable_extras().max_writes_per_s = *d;
                    } else {
                        if (d) error(k, "'max_writes_per_s' must be 0 (no limit) or more");
                        broken = true;
                    }
                } else if (key == "writable") {
                    if (const auto b = boolean(value, key, k)) {
                        spec.writable = *b;
                    } else {
                        broken = true;
                    }
                } else if (key == "min" || key == "max") {
                    const auto d = number(value, key, k);
                    if (!d) {
                        broken = true;
                    } else if (key == "min") {
                        spec.mutable_extras().min = *d;
                    } else {
                        spec.mutable_extras().max = *d;
                    }
                } else if (key == "initial") {
                    initial.emplace(value);
                    initial_mark = k;
                }
            });
        if (!node.is_map()) return std::nullopt;
        for (const std::string_view required : {"name", "address", "type"}) {
            if (!tag.marks.contains(required)) {
                error(tag.marks.node, label() + " lacks " + in_quotes(required));
                broken = true;
            }
        }
        if (initial && !broken) {
            if (auto value = read_initial(*initial, spec.type, initial_mark)) {
                spec.mutable_extras().initial = *value;
            } else {
                broken = true;
            }
        }
        if (broken) return std::nullopt;
        return tag;
    }

    /// `initial` as the tag's type holds it. Out-of-range values are kept (as int64 or double)
    /// for validate() to report against the type's range.
    std::optional<core::plan::Value> read_initial(const Node& value, TagType type, const Mark& at) {
        const std::string_view text = value.scalar();
        switch (type) {
            case TagType::bit: {
                if (text == "0") return core::plan::Value{false};
                if (text == "1") return core::plan::Value{true};
                if (const auto b = boolean(value, "initial", at)) return core::plan::Value{*b};
                return std::nullopt;
            }
            case TagType::real:
            case TagType::lreal: {
                const auto d = number(value, "initial", at);
                if (!d) return std::nullopt;
                if (type == TagType::real && std::fabs(*d) <= std::numeric_limits<float>::max()) {
                    return core::plan::Value{static_cast<float>(*d)};
                }
                return core::plan::Value{*d};
            }
            default: {
                if (const auto n = parse_integer<std::int64_t>(text)) {
                    if (core::plan::type_min(type) >= 0 && *n >= 0) {
                        return core::plan::Value{static_cast<std::uint64_t>(*n)};
                    }
                    return core::plan::Value{*n};
                }
                if (const auto n = parse_integer<std::uint64_t>(text)) {
                    return core::plan::Value{*n};
                }
                error(at, "expected an integer for 'initial'");
                return std::nullopt;
            }
        }
    }

    /// docs/protocol.md §6: the rows of the point list whose Node is this exchange.
    void read_points(const std::string& points, ExchangeConfig& exchange) {
        const Mark& at = exchange.marks.of("points");
        const std::filesystem::path path = dir_ / points;
        const std::string key = path.lexically_normal().string();
        auto it = point_lists_.find(key);
        if (it == point_lists_.end()) {
            auto text = read_file(path.string(), "point list " + in_quotes(path.string()));
            if (!text) {
                error(at, text.error());
                point_lists_.emplace(key, nullptr);
                return;
            }
            auto loaded = std::make_unique<LoadedPoints>(
                core::config::parse_point_list(text.value(), path.string()));
            // Errors of a file shared by several exchanges are reported once.
            diagnostics_.insert(diagnostics_.end(), loaded->list.errors.begin(),
                                loaded->list.errors.end());
            it = point_lists_.emplace(key, std::move(loaded)).first;
        }
        if (!it->second) return;
        const auto& [list, index] = *it->second;
        const auto rows = index.rows_of(exchange.spec.name);
        exchange.tags.reserve(exchange.tags.size() + rows.size());
        for (const auto row_index : rows) {
            const auto& row = list.rows[row_index];
            TagConfig tag;
            tag.spec = row.tag;
            tag.spec.writable = row.write;
            tag.marks.node = row.mark;
            exchange.tags.push_back(std::move(tag));
        }
        if (rows.empty() && list.errors.empty()) {
            error(at, "point list " + in_quotes(points) + " has no rows whose Node is " +
                          in_quotes(exchange.spec.name));
        }
    }

    /// A point list read once for all the exchanges that name it, with its rows by Node.
    struct LoadedPoints {
        explicit LoadedPoints(core::config::PointList parsed)
            : list(std::move(parsed)), index(list) {}
        core::config::PointList list;
        core::config::PointIndex index;  ///< views into `list`: both live and die together
    };

    FileName file_;  ///< shared by every mark of the file
    std::filesystem::path dir_;
    std::filesystem::path syntax_cache_dir_;
    Diagnostics diagnostics_;
    std::map<std::string, std::unique_ptr<LoadedPoints>> point_lists_;  ///< null: unreadable
};

}  // namespace

core::Result<Config, Diagnostics> load_config(const std::string& path, const LoadOptions& options) {
    auto text = read_file(path, "the configuration");
    if (!text) {
        Diagnostics unreadable;
        unreadable.push_back({Mark{path, 0, 0}, text.error()});
        return core::fail(std::move(unreadable));
    }
    return Loader(path, options.syntax_cache_dir).load(text.value());
}

core::Result<Config, Diagnostics> load_config_text(const std::string& text,
                                                   const std::string& file) {
    return Loader(file).load(text);
}

}  // namespace eip2mqtt::adapters::yaml
