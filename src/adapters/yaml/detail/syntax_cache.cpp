#include "adapters/yaml/detail/syntax_cache.hpp"

#include <spdlog/spdlog.h>

#include <functional>
#include <system_error>

namespace eip2mqtt::adapters::yaml::detail {

std::filesystem::path syntax_cache_file(const std::filesystem::path& cache_dir,
                                        const std::string& config_path) {
    std::error_code ec;
    auto absolute = std::filesystem::absolute(config_path, ec);
    if (ec) absolute = config_path;
    const auto hash = std::hash<std::string>{}(absolute.lexically_normal().string());
    return cache_dir / fmt::format("{}-{:016x}.tree", absolute.filename().string(), hash);
}

Tree parse_with_cache(const std::string& text, const std::string& config_path,
                      const std::filesystem::path& cache_dir) {
    if (cache_dir.empty()) return Tree::parse(text);
    const auto file = syntax_cache_file(cache_dir, config_path);
    std::string why;
    if (auto cached = Tree::load(file, text, why)) {
        spdlog::info("{}: unchanged since its YAML syntax was cached in {}", config_path,
                     file.string());
        return std::move(*cached);
    }
    if (!why.empty()) {
        spdlog::info("{}: parsing; the cached YAML syntax in {} is not used ({})", config_path,
                     file.string(), why);
    }
    Tree tree = Tree::parse(text);  // a syntax error throws: nothing is saved
    std::error_code ec;
    if (std::filesystem::create_directories(cache_dir, ec)) {
        // Made here (systemd makes its CacheDirectory= itself): the trees hold the configuration.
        std::filesystem::permissions(cache_dir, std::filesystem::perms::owner_all,
                                     std::filesystem::perm_options::replace, ec);
    }
    const auto failed = ec ? "creating the directory: " + ec.message() : tree.save(file, text);
    if (!failed.empty()) {
        spdlog::warn("{}: cannot cache its YAML syntax in {} ({}); the next start parses again",
                     config_path, file.string(), failed);
    }
    return tree;
}

}  // namespace eip2mqtt::adapters::yaml::detail
