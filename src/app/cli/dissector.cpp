// `eip2mqtt dissector -c FILE [-o eip2mqtt.lua]`: the Wireshark plugin of a configuration.

#include <cstddef>
#include <fstream>
#include <ostream>

#include "eip2mqtt/adapters/yaml/load_config.hpp"
#include "eip2mqtt/app/cli/commands.hpp"
#include "eip2mqtt/app/cli/dissector/lua_dissector.hpp"
#include "eip2mqtt/core/config/config.hpp"

namespace eip2mqtt::app {

int run_dissector(const DissectorOptions& options, std::ostream& out, std::ostream& err) {
    const auto config = adapters::yaml::load_config(options.config_path);
    if (!config) {
        for (const auto& diagnostic : config.error()) err << diagnostic.to_string() << "\n";
        err << config.error().size() << " error(s)\n";
        return 1;
    }
    const auto plans = core::config::make_plans(*config);
    const dissector::DissectorSettings settings{config->eip.port, config->eip.commands.port,
                                                config->gateway.exchange_defaults.clock_tolerance,
                                                options.config_path};
    const auto text = dissector::lua_dissector(plans, settings);
    std::ofstream file(options.output, std::ios::binary | std::ios::trunc);
    file << text;
    file.close();
    if (!file) {
        err << "eip2mqtt: cannot write " << options.output << "\n";
        return 1;
    }
    std::size_t tags = 0;
    for (const auto& plan : plans) tags += plan.tags.size();
    out << "wrote " << options.output << ": " << plans.size()
        << (plans.size() == 1 ? " exchange, " : " exchanges, ") << tags
        << (tags == 1 ? " tag" : " tags") << " (tshark -X lua_script:" << options.output
        << ", or copy it to ~/.local/lib/wireshark/plugins/)\n";
    return 0;
}

}  // namespace eip2mqtt::app
