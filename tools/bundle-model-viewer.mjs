// Bundles three, its orbit controls and urdf-loader into one minified ES module for the
// 3D model viewer, keeping only what the viewer uses (tools/model-viewer-libraries.mjs)
// and the STL loader; the Collada loader urdf-loader imports is replaced by a stub.
// Run by tools/copy-vendor.sh:  node tools/bundle-model-viewer.mjs OUTFILE
import { build } from "esbuild";
import { fileURLToPath } from "node:url";
import { dirname, join } from "node:path";
import { gzipSync } from "node:zlib";
import { readFileSync } from "node:fs";

const here = dirname(fileURLToPath(import.meta.url));
const outfile = process.argv[2];
if (!outfile) {
  console.error("usage: node tools/bundle-model-viewer.mjs OUTFILE");
  process.exit(2);
}

const noCollada = {
  name: "no-collada",
  setup(build) {
    build.onResolve({ filter: /\/ColladaLoader\.js$/ }, () => ({
      path: join(here, "no-collada-loader.mjs"),
    }));
  },
};

await build({
  entryPoints: [join(here, "model-viewer-libraries.mjs")],
  bundle: true,
  minify: true,
  format: "esm",
  target: "es2020",
  legalComments: "eof",
  plugins: [noCollada],
  outfile,
  logLevel: "warning",
});

const bytes = readFileSync(outfile);
console.log(`bundle-model-viewer: ${outfile}: ${bytes.length} bytes, ` +
            `${gzipSync(bytes, { level: 9 }).length} gzipped`);
