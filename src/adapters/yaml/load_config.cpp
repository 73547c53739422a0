#include "eip2mqtt/adapters/yaml/load_config.hpp"

#include <utility>

#include "adapters/yaml/detail/loader.hpp"
#include "adapters/yaml/detail/read_file.hpp"

namespace eip2mqtt::adapters::yaml {

using core::config::Config;
using core::config::Diagnostics;
using core::config::Mark;

core::Result<Config, Diagnostics> load_config(const std::string& path) {
    return load_config(path, {});
}

core::Result<Config, Diagnostics> load_config(const std::string& path, std::stop_token stop) {
    auto text = detail::read_file(path, "the configuration");
    if (!text) {
        Diagnostics unreadable;
        unreadable.push_back({Mark{path, 0, 0}, text.error()});
        return core::fail(std::move(unreadable));
    }
    return detail::Loader(path, std::move(stop)).load(text.value());
}

core::Result<Config, Diagnostics> load_config_text(const std::string& text,
                                                   const std::string& file) {
    return detail::Loader(file).load(text);
}

}  // namespace eip2mqtt::adapters::yaml
