#pragma once
/// The commands of the `eip2mqtt` binary (docs/commissioning.md, "Commands"). Each returns the
/// process exit status.

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace eip2mqtt::app {

/// `check -c FILE`: prints every error with file:line:column to `err` (exit 1), or, when valid,
/// each exchange's byte map and topics to `out` (exit 0).
int run_check(const std::string& config_path, std::ostream& out, std::ostream& err);

struct RunOptions {
    std::string config_path;
    std::string log_level;  ///< overrides gateway.log_level when not empty
};
/// `run -c FILE`: the daemon; returns when stopped by SIGTERM/SIGINT.
int run_gateway(const RunOptions& options);

struct SimOptions {
    std::string config_path;
    std::string target = "127.0.0.1";  ///< where the consumed exchanges are sent
    int port = 0;                      ///< 0: eip.port of the configuration
    /// Where it answers the command protocol, on eip.bind: -1, eip.commands.port when
    /// eip.commands.enabled, else nowhere; 0: nowhere; otherwise this port.
    int commands_port = -1;
    double duration_s = 0;  ///< 0: until SIGINT/SIGTERM
    std::string log_level = "info";
};
/// `sim -c FILE`: sends every consumed exchange of the configuration with changing values, and
/// answers the command protocol (docs/protocol.md §9) as a PLC would, describing them (produced,
/// from its point of view; never written: writes are answered `not_permitted`).
int run_sim(const SimOptions& options);

struct DiscoverOptions {
    std::vector<std::string> hosts;  ///< `host` or `host:port`
    int port = 7937;                 ///< for hosts without a port
    int timeout_ms = 500;            ///< per attempt
    int attempts = 3;                ///< per request
    bool yaml = false;
};
/// `discover HOST...`: asks each node on the command port for its Capabilities, every page of its
/// Summary and the Retrieve Configuration of each exchange (docs/protocol.md §9). Prints to `out`
/// a table per node (producer id, exchange id, mode, period, length, destination, port,
/// signature, state), saying which exchanges it could not retrieve and why, and a node that does
/// not answer as such; with `yaml` instead the skeletons of the exchanges the nodes produce
/// (adapters::yaml::discovered_skeleton), ready for `check`. Returns 0 when every node answered
/// and every exchange was retrieved, 1 otherwise, 2 when a host does not resolve.
int run_discover(const DiscoverOptions& options, std::ostream& out, std::ostream& err);

/// `import-points FILE.csv`: prints to `out` a complete configuration with one exchange per Node
/// of the point list (consumed for Read rows, produced for Write rows), its producer ids,
/// exchange ids and destinations marked `# TODO`. Bad rows, and Nodes mixing Read and Write,
/// go to `err` with file:line (exit 1, nothing printed to `out`). A result that would fail
/// `check` (overlapping tags...) is printed all the same, its errors on `err` (exit 1).
int run_import_points(const std::string& csv_path, std::ostream& out, std::ostream& err);

struct SniffOptions {
    std::string interface = "any";  ///< where to capture; "any": every interface
    std::string bind;               ///< when not empty: only datagrams sent to this IPv4 address
    int port = 0;                   ///< 0: eip.port of the configuration, else 18246
    std::string config_path;        ///< optional: decode the tags of the configured exchanges
    double duration_s = 0;          ///< 0: until SIGINT/SIGTERM
    double interval_s = 1;          ///< seconds between statistics tables; > 0
    std::uint64_t count = 0;        ///< stop after this many datagrams; 0: no limit
    bool yaml = false;              ///< end with the skeleton of unconfigured exchanges
};
/// `sniff`: a live decoder. Captures passively (libpcap: it needs CAP_NET_RAW) the UDP datagrams
/// to the port, received or sent by this host, so it runs beside a gateway without taking any of
/// its datagrams; without the privilege it says how to get it and returns 1, never binding the
/// port. Prints to `out` one line per datagram (receive time, source, header fields, data
/// length; or why it is malformed), with `config_path` the decoded tags of the exchange matching
/// its key (consumed or produced), and every `interval_s` a table per exchange (rate, mean
/// period, jitter, missed, duplicates, out of order; docs/protocol.md §4 rule 6). With a
/// configuration it also joins eip.multicast (a socket that joins and receives nothing), so the
/// groups' traffic reaches the host. Returns when stopped, after `duration_s` or after `count`
/// datagrams, with a last table; with `yaml`, then the YAML skeleton
/// (adapters::yaml::yaml_skeleton) of every exchange seen that the configuration lacks, its
/// destinations read from the captured IP headers.
int run_sniff(const SniffOptions& options, std::ostream& out);

struct DissectorOptions {
    std::string config_path;
    std::string output = "eip2mqtt.lua";
};
/// `dissector -c FILE`: writes the Wireshark plugin of the configuration (dissector::lua_dissector)
/// to `output` and says so on `out`, with how many exchanges and tags it decodes. A configuration
/// error goes to `err` as with `check` (exit 1), as does a file it cannot write.
int run_dissector(const DissectorOptions& options, std::ostream& out, std::ostream& err);

}  // namespace eip2mqtt::app
