#!/usr/bin/env bash
# Copies the front-end files the pages load from node_modules into assets/vendor/, where
# Jekyll publishes them with the site. No page loads anything from a CDN.
#
# Copied: KaTeX (stylesheet, fonts, script, auto-render extension) and its licence.
# assets/vendor/ is rebuilt from scratch each time and is not committed.
set -euo pipefail
cd "$(dirname "$0")/.."

katex=node_modules/katex/dist
if [ ! -f "$katex/katex.min.js" ]; then
    echo "copy-vendor: $katex/katex.min.js not found: node_modules is missing or incomplete." >&2
    echo "copy-vendor: run 'make setup' (it runs npm ci) first." >&2
    exit 1
fi

out=assets/vendor
rm -rf "$out"
mkdir -p "$out/katex/contrib" "$out/katex/fonts"

cp "$katex/katex.min.css" "$katex/katex.min.js" "$out/katex/"
cp "$katex/contrib/auto-render.min.js" "$out/katex/contrib/"
# katex.min.css names each font in woff2, woff and ttf; browsers fetch one of them.
cp "$katex"/fonts/KaTeX_* "$out/katex/fonts/"
cp node_modules/katex/LICENSE "$out/katex/"

echo "copy-vendor: KaTeX $(node -p 'require("./node_modules/katex/package.json").version' 2>/dev/null || echo '?') -> $out/katex"

# The site search (assets/js/search.js) loads lunr on the first use of the search box.
if [ ! -f node_modules/lunr/lunr.min.js ]; then
    echo "copy-vendor: node_modules/lunr/lunr.min.js not found: run 'make setup' first." >&2
    exit 1
fi
mkdir -p "$out/lunr"
cp node_modules/lunr/lunr.min.js node_modules/lunr/LICENSE "$out/lunr/"
