// Drives Debian's chromium through the status page's list of exchanges (puppeteer-core) for
// tests/integration/12_status_page_browser_test.cpp, and says what it saw, one JSON line: the
// count, the rows of the first page and of the next, the rows a search leaves, and the first
// row once the name column is clicked (sorted the other way). Each wait is on the page's
// content, bounded in time.
//
//   node status_list.js CHROMIUM URL SEARCH
"use strict";
const { launch, watchedPage } = require("./headless");

const [chromium, url, search] = process.argv.slice(2);

async function main() {
  const errors = [];
  const browser = await launch(chromium);
  const seen = {};
  try {
    const page = await watchedPage(browser, errors);
    await page.goto(url);
    const rows = () => page.$$eval("tr.exchange", (r) => r.map((x) => x.dataset.name));
    await page.waitForFunction(() => document.querySelectorAll("tr.exchange").length > 0,
      { timeout: 30000 });
    seen.count = await page.$eval("#count", (e) => e.textContent);
    seen.first_page = await rows();
    await page.click("#next");
    await page.waitForFunction((n) => document.querySelector("tr.exchange").dataset.name !== n,
      { timeout: 30000 }, seen.first_page[0]);
    seen.next_page = await rows();
    await page.type("#search", search);
    // Drawn again once the search filtered the list: its count changes.
    await page.waitForFunction((s, count) => document.getElementById("count").textContent !== count &&
      Array.from(document.querySelectorAll("tr.exchange")).every((r) => r.dataset.name.includes(s)),
    { timeout: 30000 }, search, seen.count);
    seen.searched = await rows();
    await page.click('th[data-key="name"]');
    await page.waitForFunction((n) => document.querySelector("tr.exchange").dataset.name !== n,
      { timeout: 30000 }, seen.searched[0]);
    seen.sorted_first = (await rows())[0];
  } finally {
    await browser.close();
  }
  seen.errors = errors;
  process.stdout.write(JSON.stringify(seen) + "\n");
}

main().catch((e) => {
  process.stderr.write(String(e && e.stack ? e.stack : e) + "\n");
  process.exit(1);
});
