#pragma once
/// The YAML syntax cache: yaml-cpp's parse of a configuration, kept in a directory (systemd's
/// CacheDirectory=, or `--cache-dir`) and used instead of parsing again while the file's bytes
/// are the same. Only yaml-cpp's syntax pass is skipped: every check, point list and plan is
/// made again from the tree at every load, so a cached start behaves exactly as a parsed one.
///
/// Module-private to src/adapters/yaml.

#include <filesystem>
#include <string>

#include "adapters/yaml/detail/tree.hpp"

namespace eip2mqtt::adapters::yaml::detail {

/// Where the tree of the configuration `config_path` is kept in `cache_dir`: the file's name
/// and a hash of its absolute path, so that configurations of the same name do not collide.
std::filesystem::path syntax_cache_file(const std::filesystem::path& cache_dir,
                                        const std::string& config_path);

/// The tree of `text`, the content of `config_path`: loaded from `cache_dir` when saved there
/// for this very text, otherwise parsed and then saved (a failure to save is logged, never
/// fatal). An empty `cache_dir` only parses. Throws YAML::Exception, as Tree::parse.
Tree parse_with_cache(const std::string& text, const std::string& config_path,
                      const std::filesystem::path& cache_dir);

}  // namespace eip2mqtt::adapters::yaml::detail
