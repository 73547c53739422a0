#include "adapters/yaml/detail/point_lists.hpp"

#include <utility>

#include "adapters/yaml/detail/read_file.hpp"

namespace eip2mqtt::adapters::yaml::detail {

const LoadedPoints* PointLists::find(const std::string& points, const Mark& at, Reader& reader) {
    const std::filesystem::path path = dir_ / points;
    const std::string key = path.lexically_normal().string();
    auto it = lists_.find(key);
    if (it == lists_.end()) {
        auto text = read_file(path.string(), "point list " + in_quotes(path.string()));
        if (!text) {
            reader.error(at, text.error());
            lists_.emplace(key, nullptr);
            return nullptr;
        }
        auto loaded = std::make_unique<LoadedPoints>(
            core::config::parse_point_list(text.value(), path.string()));
        // Errors of a file shared by several exchanges are reported once.
        reader.report(loaded->list.errors);
        it = lists_.emplace(key, std::move(loaded)).first;
    }
    return it->second.get();
}

}  // namespace eip2mqtt::adapters::yaml::detail
