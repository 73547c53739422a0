// Parses the command line, runs one command, and holds the process's only catch-all.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <functional>
#include <iostream>
#include <string>

#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/logging.hpp"

namespace {

using namespace eip2mqtt::app;

/// A subcommand, and what it does when the command line names it.
struct Command {
    CLI::App* app;
    std::function<int()> run;
};

/// Every command's options, filled in by CLI11 before one of them runs.
struct Options {
    RunOptions run;
    std::string check_path;
    SimOptions sim;
    std::string points_path;
    SniffOptions sniff;
    DiscoverOptions discover;
    DissectorOptions dissector;
};

CLI::App* add_run(CLI::App& cli, RunOptions& run) {
    auto* run_cmd = cli.add_subcommand("run", "Run the gateway daemon (default command)");
    // Options of the default command are also accepted without `run`.
    cli.add_option("-c,--config", run.config_path, "Configuration file");
    cli.add_option("--log-level", run.log_level, "Override gateway.log_level");
    run_cmd->add_option("-c,--config", run.config_path, "Configuration file")->required();
    run_cmd->add_option("--log-level", run.log_level, "Override gateway.log_level");
    return run_cmd;
}

Command add_check(CLI::App& cli, std::string& check_path) {
    auto* check_cmd = cli.add_subcommand("check", "Validate a configuration and show its layout");
    check_cmd->add_option("-c,--config", check_path, "Configuration file")->required();
    return {check_cmd, [&check_path] {
                // Standard output is the layout report: any log line goes to standard error.
                setup_logging("warn");
                return run_check(check_path, std::cout, std::cerr);
            }};
}

Command add_sim(CLI::App& cli, SimOptions& sim) {
    auto* sim_cmd = cli.add_subcommand("sim", "Send the consumed exchanges of a configuration");
    sim_cmd->add_option("-c,--config", sim.config_path, "Configuration file")->required();
    sim_cmd->add_option("--target", sim.target, "Destination address")->capture_default_str();
    sim_cmd->add_option("--port", sim.port, "Destination port (default: eip.port)");
    sim_cmd->add_option("--commands-port", sim.commands_port,
                        "Answer the command protocol on this port (0: not at all; default: "
                        "eip.commands.port when eip.commands.enabled)");
    sim_cmd->add_option("--duration", sim.duration_s, "Seconds to run (default: until stopped)");
    sim_cmd->add_option("--log-level", sim.log_level, "Log level")->capture_default_str();

    return {sim_cmd, [&sim] { return run_sim(sim); }};
}

Command add_import_points(CLI::App& cli, std::string& points_path) {
    auto* import_cmd =
        cli.add_subcommand("import-points", "Convert a SCADA point list (CSV) into YAML exchanges");
    import_cmd->add_option("FILE", points_path, "Point list CSV file")->required();

    return {import_cmd,
            [&points_path] { return run_import_points(points_path, std::cout, std::cerr); }};
}

Command add_sniff(CLI::App& cli, SniffOptions& sniff) {
    auto* sniff_cmd =
        cli.add_subcommand("sniff", "Print received datagrams and per-exchange statistics");
    sniff_cmd->add_option("--port", sniff.port, "UDP port (default: eip.port with -c, else 18246)");
    sniff_cmd->add_option("--interface", sniff.interface,
                          "Interface to capture on (default: any, every interface)");
    sniff_cmd->add_option("--bind", sniff.bind,
                          "Only datagrams sent to this address (default: to any address)");
    sniff_cmd->add_option("-c,--config", sniff.config_path, "Configuration: decode its tags");
    sniff_cmd->add_option("--duration", sniff.duration_s,
                          "Seconds to run (default: until stopped)");
    sniff_cmd->add_option("--interval", sniff.interval_s, "Seconds between statistics tables")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    sniff_cmd->add_option("--count", sniff.count, "Stop after this many datagrams")
        ->check(CLI::PositiveNumber);
    sniff_cmd->add_flag("--yaml", sniff.yaml,
                        "End with YAML for the exchanges seen that the configuration lacks");

    return {sniff_cmd, [&sniff] { return run_sniff(sniff, std::cout); }};
}

Command add_discover(CLI::App& cli, DiscoverOptions& discover) {
    auto* discover_cmd = cli.add_subcommand(
        "discover", "Ask nodes for their exchanges on the command port (UDP 7937)");
    discover_cmd->add_option("HOST", discover.hosts, "Nodes to ask: host or host:port")->required();
    discover_cmd->add_option("--port", discover.port, "Command port of hosts given without one")
        ->capture_default_str()
        ->check(CLI::Range(1, 65535));
    discover_cmd->add_option("--timeout-ms", discover.timeout_ms, "Wait per attempt")
        ->capture_default_str()
        ->check(CLI::Range(1, 60000));
    discover_cmd->add_option("--attempts", discover.attempts, "Attempts per request")
        ->capture_default_str()
        ->check(CLI::Range(1, 10));
    discover_cmd->add_flag("--yaml", discover.yaml,
                           "Print YAML skeletons of the exchanges the nodes produce");

    return {discover_cmd, [&discover] { return run_discover(discover, std::cout, std::cerr); }};
}

Command add_dissector(CLI::App& cli, DissectorOptions& dissector) {
    auto* dissector_cmd = cli.add_subcommand(
        "dissector", "Write a Wireshark plugin that decodes the configured exchanges' tags");
    dissector_cmd->add_option("-c,--config", dissector.config_path, "Configuration file")
        ->required();
    dissector_cmd->add_option("-o,--output", dissector.output, "Plugin file to write")
        ->capture_default_str();

    return {dissector_cmd, [&dissector] {
                setup_logging("warn");
                return run_dissector(dissector, std::cout, std::cerr);
            }};
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App cli{"eip2mqtt: EIP (Ethernet Global Data) to MQTT gateway"};
    cli.set_version_flag("--version", std::string("eip2mqtt ") + EIP2MQTT_VERSION);
    cli.require_subcommand(0, 1);

    Options options;
    add_run(cli, options.run);
    const Command commands[] = {
        add_check(cli, options.check_path),          add_sim(cli, options.sim),
        add_import_points(cli, options.points_path), add_sniff(cli, options.sniff),
        add_discover(cli, options.discover),         add_dissector(cli, options.dissector),
    };

    try {
        cli.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return cli.exit(e);
    }

    try {
        for (const auto& command : commands) {
            if (*command.app) return command.run();
        }
        if (options.run.config_path.empty()) {
            std::cerr << "eip2mqtt: no configuration given (use -c FILE); see --help\n";
            return 2;
        }
        return run_gateway(options.run);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "eip2mqtt: fatal: %s\n", e.what());
        return 1;
    }
}
