// Typesets formulas with KaTeX for the site build (_plugins/math.rb runs it once a build).
//
//   echo '[{"tex": "a^2", "display": false}]' | node tools/render-math.mjs
//
// Reads a JSON array of {tex, display} on stdin and writes an array of the same length:
// {html} for each formula typeset, {error} for one KaTeX cannot typeset (the plugin then
// stops the build naming the page). Exits 2 if KaTeX itself cannot be loaded.
import { readFileSync } from "node:fs";

let katex;
try {
  ({ default: katex } = await import("katex"));
} catch (error) {
  console.error(`render-math.mjs: cannot load the katex package (${error.message}); run 'make setup'.`);
  process.exit(2);
}

const items = JSON.parse(readFileSync(0, "utf8"));
const results = items.map(({ tex, display }) => {
  try {
    return {
      html: katex.renderToString(tex, {
        displayMode: Boolean(display),
        throwOnError: true,
        // What KaTeX would only warn about (Unicode text in math mode, say) is an error too.
        strict: "error",
        output: "htmlAndMathml",
      }),
    };
  } catch (error) {
    return { error: error.message };
  }
});
process.stdout.write(JSON.stringify(results));
