// What the browser tests' drivers share: Debian's chromium started headless by puppeteer-core
// (no browser download), and a page that collects every console error and uncaught exception.
"use strict";
const puppeteer = require("puppeteer-core");

/// Debian's chromium at `executable`, headless, in a 1200 x 900 window.
function launch(executable) {
  return puppeteer.launch({
    executablePath: executable,
    headless: true,
    args: ["--no-sandbox", "--disable-gpu", "--window-size=1200,900"],
  });
}

/// A new page of `browser` whose console errors and uncaught exceptions go to `errors`.
async function watchedPage(browser, errors) {
  const page = await browser.newPage();
  await page.setViewport({ width: 1200, height: 900 });
  page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
  page.on("pageerror", (e) => errors.push(String(e)));
  return page;
}

module.exports = { launch, watchedPage };
