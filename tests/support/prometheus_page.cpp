#include "tests/support/prometheus_page.hpp"

#include <sstream>
#include <thread>

#include "tests/support/http_get.hpp"

namespace eip2mqtt::test {

std::optional<double> prometheus_figure(std::uint16_t port, const std::string& name) {
    std::istringstream page(http_get(port, "/metrics"));
    for (std::string line; std::getline(page, line);) {
        if (line.rfind(name + " ", 0) == 0) return std::stod(line.substr(name.size() + 1));
    }
    return std::nullopt;
}

bool wait_prometheus_figure(std::uint16_t port, const std::string& name,
                            const std::function<bool(double)>& pred, std::chrono::seconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        if (const auto v = prometheus_figure(port, name); v && pred(*v)) return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
}

}  // namespace eip2mqtt::test
