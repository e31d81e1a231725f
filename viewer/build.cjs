// Bundles src/main.js and three.js into one minified IIFE, the script every viewer page inlines:
//
//   node build.cjs <output.js>
//
// esbuild's output depends only on the sources and the pinned versions in package-lock.json,
// so a rebuild reproduces the committed bundle byte for byte. three.js's licence notice
// (its `@license` comments) is kept at the end of the bundle.
const path = require("path");
const esbuild = require("esbuild");

async function main() {
  const [output] = process.argv.slice(2);
  if (!output) throw new Error("usage: node build.cjs <output.js>");
  await esbuild.build({
    entryPoints: [path.join(__dirname, "src", "main.js")],
    outfile: path.resolve(output),
    bundle: true,
    minify: true,
    format: "iife",
    target: "es2020",
    legalComments: "eof",
    charset: "utf8",
    logLevel: "warning",
  });
}

main().catch((error) => {
  console.error(error.message);
  process.exit(1);
});
