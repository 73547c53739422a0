#pragma once
/// The commands of the `eip2mqtt` binary (product.md "Command line"). Each returns the process
/// exit status.

#include <iosfwd>
#include <string>

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
    double duration_s = 0;             ///< 0: until SIGINT/SIGTERM
    std::string log_level = "info";
};
/// `sim -c FILE`: sends every consumed exchange of the configuration with changing values.
int run_sim(const SimOptions& options);

/// `import-points FILE.csv`: prints to `out` a complete configuration with one exchange per Node
/// of the point list (consumed for Read rows, produced for Write rows), its producer ids,
/// exchange ids and destinations marked `# TODO`. Bad rows, and Nodes mixing Read and Write,
/// go to `err` with file:line (exit 1, nothing printed to `out`). A result that would fail
/// `check` (overlapping tags...) is printed all the same, its errors on `err` (exit 1).
int run_import_points(const std::string& csv_path, std::ostream& out, std::ostream& err);

}  // namespace eip2mqtt::app
