#!/usr/bin/env bash
# Copies the front-end files the pages load from node_modules into assets/vendor/, where
# Jekyll publishes them with the site. No page loads anything from a CDN.
#
# Copied: KaTeX's stylesheet and fonts (the formulas are typeset at build time by
# _plugins/math.rb and tools/render-math.mjs) and its licence.
# assets/vendor/ is rebuilt from scratch each time and is not committed.
set -euo pipefail
cd "$(dirname "$0")/.."

katex=node_modules/katex/dist
if [ ! -f "$katex/katex.min.css" ]; then
    echo "copy-vendor: $katex/katex.min.css not found: node_modules is missing or incomplete." >&2
    echo "copy-vendor: run 'make setup' (it runs npm ci) first." >&2
    exit 1
fi

out=assets/vendor
rm -rf "$out"
mkdir -p "$out/katex/fonts"

cp "$katex/katex.min.css" "$out/katex/"
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

# The 3D model viewer (assets/js/model-viewer.js): one minified module holding the parts
# of three, its orbit controls and urdf-loader the viewer uses, with the STL loader and
# without the Collada loader (tools/bundle-model-viewer.mjs, with esbuild), and their
# licences (urdf-loader's npm package ships no LICENSE file: its README carries the notice).
for file in node_modules/three/build/three.module.js node_modules/urdf-loader/src/URDFLoader.js \
        node_modules/esbuild/package.json; do
    if [ ! -f "$file" ]; then
        echo "copy-vendor: $file not found: run 'make setup' (it runs npm ci) first." >&2
        exit 1
    fi
done
mkdir -p "$out/model-viewer"
node tools/bundle-model-viewer.mjs "$out/model-viewer/libraries.min.js"
cp node_modules/three/LICENSE "$out/model-viewer/LICENSE-three"
cp node_modules/urdf-loader/README.md "$out/model-viewer/README-urdf-loader.md"

version() { node -p "require('./node_modules/$1/package.json').version" 2>/dev/null || echo '?'; }
echo "copy-vendor: three $(version three), urdf-loader $(version urdf-loader) -> $out/model-viewer"

# The Simulate mode of the 3D viewer (assets/js/simulation-worker.js): MuJoCo's own
# WebAssembly build, single-threaded (the multi-threaded one needs cross-origin isolation
# headers that GitHub Pages cannot send). The worker fetches mujoco.wasm itself, so that the
# page can show the download's progress; mujoco.json gives it the file's size for that.
# The package ships no LICENSE file: its package.json names the licence (Apache-2.0, kept in
# mujoco.json), its README the authors.
mujoco=node_modules/@mujoco/mujoco
for file in "$mujoco/mujoco.js" "$mujoco/mujoco.wasm"; do
    if [ ! -f "$file" ]; then
        echo "copy-vendor: $file not found: run 'make setup' (it runs npm ci) first." >&2
        exit 1
    fi
done
mkdir -p "$out/mujoco"
cp "$mujoco/mujoco.js" "$mujoco/mujoco.wasm" "$out/mujoco/"
cp "$mujoco/README.md" "$out/mujoco/README-mujoco.md"
node -e 'const fs = require("fs"); const [from, dir] = process.argv.slice(1);
  const { version, license } = JSON.parse(fs.readFileSync(from + "/package.json"));
  fs.writeFileSync(dir + "/mujoco.json", JSON.stringify(
    { version, license, wasm_bytes: fs.statSync(dir + "/mujoco.wasm").size }) + "\n");' \
    "$mujoco" "$out/mujoco"
echo "copy-vendor: @mujoco/mujoco $(version @mujoco/mujoco) -> $out/mujoco"
