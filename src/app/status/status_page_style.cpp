// The status page's style.

#include "eip2mqtt/app/status/status_page.hpp"

namespace eip2mqtt::app::status::detail {

const std::string_view page_style = R"css(
body { font: 14px system-ui, sans-serif; margin: 0 1.5em 2em; color: #1d2329; }
header { display: flex; align-items: baseline; gap: 1em; }
h1 { font-size: 1.4em; margin: .6em 0; }
.live { padding: .1em .6em; border-radius: 1em; background: #2e7d32; color: #fff; }
.live.off { background: #b71c1c; }
dl { display: grid; grid-template-columns: max-content auto; gap: .2em 1.2em; margin: 0 0 1em; }
dt { color: #5f6b76; }
dd { margin: 0; }
.tools { display: flex; gap: .8em; align-items: center; margin: .5em 0; }
table { border-collapse: collapse; width: 100%; }
th, td { text-align: left; padding: .25em .6em; border-bottom: 1px solid #dde3e8; }
th { cursor: pointer; user-select: none; background: #f3f6f8; }
th.sorted::after { content: " \25BE"; }
th.sorted.up::after { content: " \25B4"; }
tr.exchange { cursor: pointer; }
tr.exchange:hover { background: #f7fafc; }
tr.bad td.state { color: #b71c1c; font-weight: 600; }
tr.waiting td.state { color: #8a6d00; }
td.number { text-align: right; font-variant-numeric: tabular-nums; }
tr.tags > td { background: #fafbfc; padding: .3em 1.5em .8em; }
tr.tags table th { cursor: default; }
.quality-bad, .quality-stale { color: #b71c1c; }
footer { margin-top: 2em; color: #5f6b76; }
)css";

const std::string_view page_icon =
    R"svg(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 16 16">)svg"
    R"svg(<rect width="16" height="16" rx="3" fill="#2e7d32"/>)svg"
    R"svg(<path d="M3 11h3l2-6 2 6h3" stroke="#fff" stroke-width="1.6" fill="none"/></svg>)svg";

}  // namespace eip2mqtt::app::status::detail
