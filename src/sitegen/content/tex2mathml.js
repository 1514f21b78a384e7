// Converts TeX to MathML with Temml, for the build (never shipped to the browser).
// stdin: JSON [[tex, displayMode], ...]   stdout: JSON [{"mathml": ...} | {"error": ...}, ...]
"use strict";
const temml = require("temml");

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
