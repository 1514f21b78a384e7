// Drives Firefox ESR for the browser tests (tests/engines.py): puppeteer-core over WebDriver BiDi,
// one headless browser and one tab, commands read as JSON lines on stdin, one JSON answer a line on stdout.
// argv[2]: Firefox's executable. Commands: {op: "version" | "load" | "run" | "resize" | "screenshot" |
// "click" | "press" | "type" | "errors", ...}; an answer is {value} or {error}.
"use strict";
const path = require("path");
const readline = require("readline");
const puppeteer = require(path.join(__dirname, "..", "node_modules", "puppeteer-core"));

async function main() {
  const browser = await puppeteer.launch({
    browser: "firefox",
    executablePath: process.argv[2],
    headless: true,
    // no updates or first-run checks; focus and blur events as in a window in front (headless, it is in none)
    extraPrefsFirefox: { "app.update.enabled": false, "browser.shell.checkDefaultBrowser": false, "focusmanager.testmode": true },
  });
  const page = await browser.newPage(); // the tab it starts with never has the focus: no focus events in it
  await page.bringToFront();
  const errors = []; // page errors, console errors and warnings, since the last "errors"
  page.on("pageerror", (error) => errors.push(`pageerror: ${error.message || error}`));
  page.on("console", (message) => {
    if (message.type() === "error" || message.type() === "warn") errors.push(`${message.type()}: ${message.text()}`);
  });
  const ops = {
    version: async () => browser.version(),
    load: async ({ url, settled }) => {
      await page.goto("about:blank");
      await page.goto(url, { waitUntil: "load" });
      return page.evaluate(settled); // the fonts and the scenes' data (tests/browser.py)
    },
    run: async ({ script }) => page.evaluate(script),
    resize: async ({ width, height }) => page.setViewport({ width, height }),
    screenshot: async () => page.screenshot({ encoding: "base64" }),
    click: async ({ selector }) => page.click(selector),
    press: async ({ key }) => page.keyboard.press(key),
    type: async ({ text }) => page.keyboard.type(text),
    errors: async () => errors.splice(0),
  };
  const lines = readline.createInterface({ input: process.stdin });
  for await (const line of lines) {
    const command = JSON.parse(line);
    let answer;
    try {
      const value = await ops[command.op](command);
      answer = { value: value === undefined ? null : value };
    } catch (error) {
      answer = { error: String((error && error.stack) || error) };
    }
    process.stdout.write(JSON.stringify(answer) + "\n");
  }
  await browser.close();
}

main().catch((error) => {
  process.stdout.write(JSON.stringify({ error: String((error && error.stack) || error) }) + "\n");
  process.exit(1);
});
