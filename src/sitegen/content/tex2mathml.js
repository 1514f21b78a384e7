// Converts TeX to MathML with Temml, for the build (never shipped to the browser).
// argv[2]: the path of Temml's browser build (temml.min.js, vendored in the sitegen package).
// stdin: JSON [[tex, displayMode], ...]   stdout: JSON [{"mathml": ...} | {"error": ...}, ...]
"use strict";
const fs = require("fs");
const vm = require("vm");

// The browser build defines a global `temml`; run in this context it gives the MathML of the
// package's CommonJS build byte for byte, and needs no node_modules.
vm.runInThisContext(fs.readFileSync(process.argv[2], "utf8"), { filename: process.argv[2] });
const temml = globalThis.temml;

let input = "";
process.stdin.setEncoding("utf8");
process.stdin.on("data", (chunk) => { input += chunk; });
process.stdin.on("end", () => {
  const results = JSON.parse(input).map(([tex, displayMode]) => {
    try {
      return { mathml: temml.renderToString(tex, { displayMode, throwOnError: true, annotate: false }) };
    } catch (error) {
      return { error: String(error.message || error) };
    }
  });
  process.stdout.write(JSON.stringify(results));
});
