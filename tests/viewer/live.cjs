// Drives a live session of `crane-cosim live` from its page in headless Chromium like an
// operator: waits for the simulated time to pass 2 s, switches compensation off and on again
// (key C), then moves the load set-point 0.1 m north (ArrowUp × 10) and 0.05 m up (PageUp × 5),
// and watches for 5 s of simulated time. Prints, as JSON, the session state before and after,
// the simulated time of the first move, console errors and requests that left the server.
// Saves a screenshot at the end.
//
//   node live.cjs <page URL> <screenshot.png>
const { driveLive } = require("./common.cjs");

const [url, screenshot] = process.argv.slice(2);
driveLive(url, async ({ page, console_errors, outside_requests, session, until, started }) => {
  const simulated = () => page.evaluate(() => craneViewer.time());
  await started(2.0);
  const before = await session();
  await page.keyboard.press("c");
  await until(() => craneViewer.session().compensation === false);
  await page.waitForTimeout(500);
  await page.keyboard.press("c");
  await until(() => craneViewer.session().compensation === true);
  const moved_at = await simulated();
  for (let i = 0; i < 10; i++) await page.keyboard.press("ArrowUp");
  for (let i = 0; i < 5; i++) await page.keyboard.press("PageUp");
  await until((x) => craneViewer.session().setpoint[0] > x + 0.0999, before.setpoint[0]);
  await until((t) => craneViewer.time() >= t + 5.0, moved_at);
  const after = await session();
  const drawn = await page.evaluate(() => craneViewer.drawn());
  await page.screenshot({ path: screenshot });
  process.stdout.write(JSON.stringify({ before, after, moved_at, drawn, console_errors, outside_requests }));
});
