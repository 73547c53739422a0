// The status page's HTML: the frame its script fills (status_page_script.cpp).

#include "eip2mqtt/app/status/status_page.hpp"

namespace eip2mqtt::app::status::detail {

const std::string_view page_html = R"html(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>eip2mqtt</title>
<link rel="stylesheet" href="/status.css">
<link rel="icon" href="/favicon.svg" type="image/svg+xml">
<script src="/status.js" defer></script>
</head>
<body>
<header>
  <h1>eip2mqtt <span id="gateway-id"></span></h1>
  <span id="live" class="live off">connecting</span>
</header>
<section id="gateway"><dl id="facts"></dl></section>
<section id="exchanges">
  <div class="tools">
    <input id="search" type="search" placeholder="search exchanges" aria-label="search exchanges">
    <span id="count"></span>
    <button id="previous" type="button">previous</button>
    <span id="page"></span>
    <button id="next" type="button">next</button>
  </div>
  <table id="exchange-table">
    <thead><tr>
      <th data-key="name">exchange</th><th data-key="direction">direction</th>
      <th data-key="state">state</th><th data-key="rate">datagrams/s</th>
      <th data-key="age">last datagram</th><th data-key="missed">missed</th>
      <th data-key="restarts">restarts</th><th data-key="clock">clock</th>
    </tr></thead>
    <tbody></tbody>
  </table>
</section>
<section id="writes">
  <h2>Last writes</h2>
  <table id="write-table"><thead><tr><th>time</th><th>origin</th><th>target</th>
    <th>values</th><th>result</th></tr></thead><tbody></tbody></table>
</section>
<section id="warnings">
  <h2>Last warnings</h2>
  <ol id="warning-list"></ol>
</section>
<footer>Read-only: writes go over MQTT. <a href="/api/status">/api/status</a></footer>
</body>
</html>
)html";

}  // namespace eip2mqtt::app::status::detail
