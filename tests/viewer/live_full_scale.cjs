// Drives a live session of the full-scale crane (`crane-cosim live` of a full_scale_ahc
// scenario) from its page in headless Chromium: waits for the simulated time to pass 1 s, presses
// ArrowUp (a set-point move, which the full-scale controller cannot take) and C (compensation
// off), and prints, as JSON, the session state before and after, the page's status line, what is
// drawn (tip, load, cylinders, ghost markers), console errors and requests that left the server.
// Saves a screenshot at the end.
//
//   node live_full_scale.cjs <page URL> <screenshot.png>
const { driveLive } = require("./common.cjs");

const [url, screenshot] = process.argv.slice(2);
driveLive(url, async ({ page, console_errors, outside_requests, session, until, started }) => {
  await started(1.0);
  const before = await session();
  await page.keyboard.press("ArrowUp");
  await until(() => Boolean(craneViewer.session().refused));
  await page.keyboard.press("c");
  await until(() => craneViewer.session().compensation === false);
  const after = await session();
  const status = await page.evaluate(() => document.getElementById("operator").textContent);
  const compensation_hidden = await page.evaluate(() => document.getElementById("compensation").hidden);
  const scale = await page.evaluate(() => craneViewer.scale);
  const drawn = await page.evaluate(() => ({
    ...craneViewer.drawn(),
    tip_on_screen: craneViewer.onScreen("tip"),
    load_on_screen: craneViewer.onScreen("load"),
  }));
  await page.screenshot({ path: screenshot });
  const seen = { scale, before, after, status, compensation_hidden, drawn, console_errors, outside_requests };
  process.stdout.write(JSON.stringify(seen));
});
