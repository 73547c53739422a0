#include "eip2mqtt/app/status/status_page.hpp"

namespace eip2mqtt::app::status {

const PageResource* page_resource(std::string_view path) {
    static const PageResource html{"text/html; charset=utf-8", detail::page_html};
    static const PageResource script{"text/javascript; charset=utf-8", detail::page_script};
    static const PageResource style{"text/css; charset=utf-8", detail::page_style};
    if (path == "/") return &html;
    if (path == "/status.js") return &script;
    if (path == "/status.css") return &style;
    return nullptr;
}

}  // namespace eip2mqtt::app::status
