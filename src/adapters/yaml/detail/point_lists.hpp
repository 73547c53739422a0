#pragma once
/// The point lists (docs/protocol.md §6) a configuration names, each read once for all the
/// exchanges that name it, with its rows by Node.
///
/// Module-private to src/adapters/yaml.

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include "adapters/yaml/detail/reader.hpp"
#include "eip2mqtt/core/config/point_index.hpp"
#include "eip2mqtt/core/config/point_list.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// A point list as read, with its rows by Node.
struct LoadedPoints {
    explicit LoadedPoints(core::config::PointList parsed) : list(std::move(parsed)), index(list) {}
    core::config::PointList list;
    core::config::PointIndex index;  ///< views into `list`: both live and die together
};

class PointLists {
public:
    /// `dir`: the folder of the configuration file, which the lists' names are relative to.
    explicit PointLists(std::filesystem::path dir) : dir_(std::move(dir)) {}

    /// The list named `points`, read on its first use, when its errors go to `reader` (once for
    /// a file shared by several exchanges). Null when it cannot be read: reported at `at` the
    /// first time only.
    const LoadedPoints* find(const std::string& points, const Mark& at, Reader& reader);

private:
    std::filesystem::path dir_;
    std::map<std::string, std::unique_ptr<LoadedPoints>> lists_;  ///< null: unreadable
};

}  // namespace eip2mqtt::adapters::yaml::detail
