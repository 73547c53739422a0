#pragma once
/// The configuration loader: parses the file, hands each top-level section to its reader
/// (sections.hpp), validates the model and reports every problem of the file in one run, sorted
/// by line and column.
///
/// Module-private to src/adapters/yaml.

#include <filesystem>
#include <stop_token>
#include <string>

#include "adapters/yaml/detail/point_lists.hpp"
#include "adapters/yaml/detail/reader.hpp"
#include "eip2mqtt/adapters/yaml/load_config.hpp"

namespace eip2mqtt::adapters::yaml::detail {

class Loader {
public:
    /// `stop`: the load gives up, with one diagnostic, soon after it is requested.
    explicit Loader(std::string file, std::stop_token stop = {})
        : file_(std::move(file)),
          stop_(std::move(stop)),
          reader_(file_, diagnostics_),
          point_lists_(std::filesystem::path(file_.str()).parent_path()) {}

    Loader(const Loader&) = delete;  // reader_ reports into this one's diagnostics_
    Loader& operator=(const Loader&) = delete;

    core::Result<Config, Diagnostics> load(const std::string& text);

private:
    void read_root(const Node& root, Config& config);

    FileName file_;  ///< shared by every mark of the file
    std::stop_token stop_;
    Diagnostics diagnostics_;
    Reader reader_;  ///< reports into diagnostics_
    PointLists point_lists_;
};

}  // namespace eip2mqtt::adapters::yaml::detail
