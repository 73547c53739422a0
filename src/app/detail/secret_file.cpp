#include "app/detail/secret_file.hpp"

#include <spdlog/spdlog.h>
#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace eip2mqtt::app::detail {

std::string credentials_directory() {
    const char* directory = std::getenv("CREDENTIALS_DIRECTORY");
    return directory != nullptr ? directory : "";
}

std::string first_line(const std::string& path, const std::string& what) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error("cannot read " + what);
    std::string line;
    std::getline(file, line);
    return line;
}

std::string read_secret_file(const std::string& file, std::string_view key) {
    const auto credentials = credentials_directory();
    const bool named = file.find('/') == std::string::npos;
    if (named && !credentials.empty()) {
        const auto path = credentials + "/" + file;
        return first_line(path, std::string(key) + ": the systemd credential " + file + " (" +
                                    path + "); the unit needs LoadCredential=" + file);
    }
    struct stat info {};
    if (::stat(file.c_str(), &info) == 0 && (info.st_mode & S_IROTH) != 0) {
        spdlog::warn("password file {} is readable by others; chmod o-r it", file);
    }
    std::string what = std::string(key) + " " + file;
    if (named) {
        what +=
            " (a name without a slash is a systemd credential only where $CREDENTIALS_DIRECTORY "
            "is set, in a unit with LoadCredential=" +
            file + ")";
    }
    return first_line(file, what);
}

}  // namespace eip2mqtt::app::detail
