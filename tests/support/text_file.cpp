#include "tests/support/text_file.hpp"

#include <fstream>
#include <sstream>

namespace eip2mqtt::test {

std::string read_text_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

void write_text_file(const std::string& path, const std::string& content) {
    std::ofstream(path) << content;
}

}  // namespace eip2mqtt::test
