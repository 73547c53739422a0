#pragma once
/// The status page the metrics listener serves at `/`: one HTML page, its script and its style,
/// compiled into the binary (a plant network reaches nothing outside), reading /api/events.

#include <string_view>

namespace eip2mqtt::app::status {

struct PageResource {
    std::string_view content_type;
    std::string_view text;
};

/// The page's resource at `path` (`/`, `/status.js`, `/status.css`, `/favicon.svg`), or null.
const PageResource* page_resource(std::string_view path);

namespace detail {
extern const std::string_view page_html;
extern const std::string_view page_script;
extern const std::string_view page_style;
extern const std::string_view page_icon;
}  // namespace detail

}  // namespace eip2mqtt::app::status
