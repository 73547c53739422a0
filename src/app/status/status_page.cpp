#include "eip2mqtt/app/status/status_page.hpp"

namespace eip2mqtt::app::status {

const PageResource* page_resource(std::string_view path) {
    static const PageResource html{"text/html; charset=utf-8", detail::page_html};
    static const PageResource script{"text/javascript; charset=utf-8", detail::page_script};
    static const PageResource style{"text/css; charset=utf-8", detail::page_style};
    // The page's icon, named in it: a browser would otherwise ask /favicon.ico, and log its 404.
    static const PageResource icon{"image/svg+xml", detail::page_icon};
    if (path == "/") return &html;
    if (path == "/status.js") return &script;
    if (path == "/status.css") return &style;
    if (path == "/favicon.svg") return &icon;
    return nullptr;
}

}  // namespace eip2mqtt::app::status
