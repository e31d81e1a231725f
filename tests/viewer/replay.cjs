// Opens a replay page written by `crane-cosim view` in headless Chromium and prints, as JSON,
// what it shows: console errors, requests that left the file, the time range, the crane's scale,
// the legend and the plots' titles, where the tip, load, ghost markers and cylinders are drawn
// (and the tip and load on the canvas) after seeking each requested time (read back from the
// three.js scene graph through window.craneViewer), and how much of the 3D view around the load
// changes between the first two requested times, and how far playback at 8x gets in 1 s.
// Saves a screenshot at each time.
//
//   node replay.cjs <replay.html> <screenshot prefix> <t> [<t> ...]
//
// playwright-core is found through NODE_PATH (tests/test_viewer.py points it at the
// node_modules that `cargo xtask test` installs into target/).
const path = require("path");
const { pathToFileURL } = require("url");
const { launch, watchedPage } = require("./common.cjs");

// Side (px) of the square around the load's drawn position whose pixels are compared.
const BOX = 60;

async function main() {
  const [file, prefix, ...times] = process.argv.slice(2);
  const url = pathToFileURL(path.resolve(file)).href;
  const browser = await launch();
  try {
    const { page, console_errors, outside_requests } = await watchedPage(browser, [url]);
    await page.goto(url);
    await page.waitForFunction(() => window.craneViewer && window.craneViewer.frames() > 0);
    const seen = { console_errors, outside_requests, range: await page.evaluate(() => craneViewer.range()) };
    seen.scale = await page.evaluate(() => craneViewer.scale);
    seen.legend = await page.evaluate(() => document.getElementById("legend").textContent);
    seen.plots = await page.evaluate(() => [...document.querySelectorAll("#plots canvas")].map((c) => c.title));
    seen.seeks = [];
    const shots = [];
    for (const t of times.map(Number)) {
      const drawn = await page.evaluate((t) => {
        craneViewer.seek(t);
        return {
          ...craneViewer.drawn(),
          load_on_screen: craneViewer.onScreen("load"),
          tip_on_screen: craneViewer.onScreen("tip"),
        };
      }, t);
      seen.seeks.push({ requested: t, ...drawn });
      shots.push({ pixels: await pixels(page, String(t)), at: drawn.load_on_screen });
      await page.screenshot({ path: `${prefix}-${t}.png` });
    }
    if (shots.length >= 2) {
      const [a, b] = shots;
      seen.changed_around_load = [];
      for (const at of [a.at, b.at]) seen.changed_around_load.push(await changed(page, a.pixels, b.pixels, at));
      // A corner of the view far from the crane: the background, the same at both times.
      seen.changed_in_corner = await changed(page, a.pixels, b.pixels, { x: BOX / 2 + 2, y: BOX / 2 + 2 });
    }
    // Playback: at 8x, a second of wall time moves the shown time on by several seconds.
    await page.evaluate(() => craneViewer.seek(0));
    await page.selectOption("#speed", "8");
    await page.click("#play");
    await page.waitForTimeout(1000);
    seen.played_to = await page.evaluate(() => craneViewer.time());
    process.stdout.write(JSON.stringify(seen));
  } finally {
    await browser.close();
  }
}

// Keeps a copy of the 3D view's pixels in the page (under `name`) for changed().
async function pixels(page, name) {
  await page.evaluate((name) => {
    const canvas = document.querySelector("#view canvas");
    const copy = document.createElement("canvas");
    copy.width = canvas.width;
    copy.height = canvas.height;
    const g = copy.getContext("2d");
    g.drawImage(canvas, 0, 0);
    window.shots = window.shots || {};
    window.shots[name] = g.getImageData(0, 0, copy.width, copy.height);
  }, name);
  return name;
}

// The fraction of pixels in the BOX-sided square at `at` (canvas pixels) that differ between
// the kept copies a and b.
async function changed(page, a, b, at) {
  return page.evaluate(
    ([a, b, at, box]) => {
      const [p, q] = [window.shots[a], window.shots[b]];
      let differing = 0;
      let total = 0;
      for (let y = Math.round(at.y - box / 2); y < at.y + box / 2; y++) {
        for (let x = Math.round(at.x - box / 2); x < at.x + box / 2; x++) {
          if (x < 0 || y < 0 || x >= p.width || y >= p.height) continue;
          const i = 4 * (y * p.width + x);
          total++;
          if ([0, 1, 2].some((c) => Math.abs(p.data[i + c] - q.data[i + c]) > 24)) differing++;
        }
      }
      return total ? differing / total : 0;
    },
    [a, b, at, BOX],
  );
}

main().catch((error) => {
  console.error(error.stack || String(error));
  process.exit(1);
});
