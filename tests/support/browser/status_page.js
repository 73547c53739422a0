// Drives Debian's chromium through the gateway's status page (puppeteer-core over the DevTools
// protocol) for tests/integration/12_status_page_browser_test.cpp, and says what it saw, one
// JSON line per step: the page showing every exchange, a tag's value changing on screen, the
// write log showing a write to WRITTEN (its values and result), the exchange turning stale
// once its datagrams stop, and every console error. Each wait is on the page's content,
// bounded in time.
//
//   node status_page.js CHROMIUM URL EXCHANGE TAG EXCHANGE_COUNT SCREENSHOT WRITTEN
"use strict";
const { launch, watchedPage } = require("./headless");

const [chromium, url, exchange, tag, count, screenshot, written] = process.argv.slice(2);
const say = (line) => process.stdout.write(JSON.stringify(line) + "\n");

/// The text of `tag`'s value cell in the open exchange's tags table, or null.
function valueOf(tagName) {
  for (const row of document.querySelectorAll("tr.tags tr")) {
    const cells = row.querySelectorAll("td");
    if (cells.length > 1 && cells[0].textContent === tagName) return cells[1].textContent;
  }
  return null;
}

async function main() {
  const errors = [];
  const browser = await launch(chromium);
  try {
    const page = await watchedPage(browser, errors);
    await page.goto(url + "#open=" + encodeURIComponent(exchange));
    await page.waitForFunction((n) => document.querySelectorAll("tr.exchange").length === n,
      { timeout: 30000 }, Number(count));
    const names = await page.$$eval("tr.exchange", (rows) => rows.map((r) => r.dataset.name));
    say({ step: "shown", exchanges: names });

    await page.evaluate(`window.valueOfTag = ${valueOf.toString()}`);
    await page.waitForFunction((t) => window.valueOfTag(t) !== null, { timeout: 30000 }, tag);
    const first = await page.evaluate((t) => window.valueOfTag(t), tag);
    const since = Date.now();
    // Bounded: a page that never changes says so with the same value twice.
    await page.waitForFunction((t, v) => window.valueOfTag(t) !== v, { timeout: 30000 }, tag,
      first).catch(() => null);
    const second = await page.evaluate((t) => window.valueOfTag(t), tag);
    say({ step: "changed", first: first, second: second, ms: Date.now() - since });
    const points = await page.$$eval("tr.tags svg.spark polyline",
      (lines) => lines.map((l) => l.getAttribute("points")));
    say({ step: "sparkline", lines: points.length, drawn: points.filter((p) => p !== "").length });

    // The test writes once it reads "changed"; the log shows the write once answered.
    await page.waitForFunction((values) => Array.from(document.querySelectorAll("tr.write"))
      .some((r) => r.cells[3].textContent === values && r.cells[4].textContent !== "pending"),
    { timeout: 60000 }, written);
    const write = await page.$$eval("tr.write", (rows, values) => {
      const r = rows.find((x) => x.cells[3].textContent === values);
      return { origin: r.cells[1].textContent, target: r.cells[2].textContent,
        values: r.cells[3].textContent, result: r.cells[4].textContent };
    }, written);
    say(Object.assign({ step: "write" }, write));

    await page.waitForFunction((name) => {
      const row = document.querySelector(`tr.exchange[data-name="${name}"]`);
      return row !== null && row.classList.contains("bad");
    }, { timeout: 60000 }, exchange);
    const state = await page.$eval(`tr.exchange[data-name="${exchange}"] td.state`,
      (cell) => cell.textContent);
    say({ step: "stale", state: state });
    // The log's warning of it, among the last warnings below the tables.
    await page.waitForFunction((name) => Array.from(document.querySelectorAll("#warning-list li"))
      .some((li) => li.textContent.includes("exchange " + name + " is stale")),
    { timeout: 30000 }, exchange).catch(() => null);
    say({ step: "warnings", lines: await page.$$eval("#warning-list li",
      (items) => items.map((li) => li.textContent)) });
    await page.screenshot({ path: screenshot });
  } finally {
    await browser.close();
  }
  say({ step: "done", errors: errors });
}

main().catch((e) => {
  say({ step: "failed", error: String(e && e.stack || e) });
  process.exit(1);
});
