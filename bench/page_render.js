// Scenario 16's time to first render: Debian's chromium, headless (puppeteer-core, installed for
// the browser test under tests/support/browser), loads the status page RUNS times, each in a
// fresh browser context (nothing cached), with EXCHANGE open. In the page, before its script
// runs, a MutationObserver notes when the first exchange row and then EXCHANGE's TAGS tag rows
// are in the document (milliseconds since navigation started, the browser's own clock); the
// first contentful paint comes from the browser's paint timing. Every wait is bounded.
//
//   node page_render.js CHROMIUM URL EXCHANGE TAGS RUNS
// prints one JSON line: {"runs":[{"rows_ms":..,"tags_ms":..,"fcp_ms":..,"exchanges":..},..]}
"use strict";
const path = require("path");
const puppeteer = require(path.join(__dirname, "..", "tests", "support", "browser",
  "node_modules", "puppeteer-core"));

const [chromium, url, exchange, tags, runs] = process.argv.slice(2);

function watch(wanted) {
  window.renderMarks = {};
  new MutationObserver(() => {
    const marks = window.renderMarks;
    if (marks.rows === undefined && document.querySelector("tr.exchange")) {
      marks.rows = performance.now();
    }
    if (marks.tags === undefined &&
        document.querySelectorAll("tr.tags tr > td:first-child").length >= wanted) {
      marks.tags = performance.now();
    }
  }).observe(document, { childList: true, subtree: true });
}

async function once(browser) {
  const context = await browser.createBrowserContext();
  try {
    const page = await context.newPage();
    await page.setViewport({ width: 1200, height: 900 });
    await page.evaluateOnNewDocument(watch, Number(tags));
    await page.goto(url + "#open=" + encodeURIComponent(exchange));
    await page.waitForFunction(() => window.renderMarks.tags !== undefined, { timeout: 60000 });
    return await page.evaluate(() => ({
      rows_ms: window.renderMarks.rows,
      tags_ms: window.renderMarks.tags,
      fcp_ms: (performance.getEntriesByName("first-contentful-paint")[0] || {}).startTime,
      exchanges: document.querySelectorAll("tr.exchange").length,
    }));
  } finally {
    await context.close();
  }
}

async function main() {
  const browser = await puppeteer.launch({
    executablePath: chromium,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--window-size=1200,900"],
  });
  const results = [];
  try {
    for (let i = 0; i < Number(runs); ++i) results.push(await once(browser));
  } finally {
    await browser.close();
  }
  process.stdout.write(JSON.stringify({ runs: results }) + "\n");
}

main().catch((e) => {
  process.stderr.write(String(e && e.stack ? e.stack : e) + "\n");
  process.exit(1);
});
