// Opens an unpacked FMU's documentation/index.html in headless Chromium and prints, as JSON, what
// a reader sees: title, headings, text, the variable table, every link and whether it resolves
// inside the unpacked archive, any request that left it, console errors and whether the page
// scrolls sideways. Saves a screenshot of the first screen.
//
//   node inspect.cjs <unpacked FMU folder> <screenshot.png>
//
// playwright-core is found through NODE_PATH (tests/test_documentation.py points it at the
// node_modules that `cargo xtask test` installs into target/).
const fs = require("fs");
const path = require("path");
const { pathToFileURL, fileURLToPath } = require("url");
const { chromium } = require("playwright-core");
const { watchedPage } = require("../viewer/common.cjs");

async function main() {
  const [folder, screenshot] = process.argv.slice(2).map((p) => path.resolve(p));
  const page_url = pathToFileURL(path.join(folder, "documentation", "index.html")).href;
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-background-networking"],
  });
  try {
    const { page, console_errors, outside_requests } = await watchedPage(browser, [pathToFileURL(folder).href + "/"]);
    await page.goto(page_url);
    const seen = await page.evaluate(() => ({
      title: document.title,
      h1: [...document.querySelectorAll("h1")].map((h) => h.innerText.trim()),
      headings: [...document.querySelectorAll("#model h2, #model h3, #model h4")].map((h) => h.innerText.trim()),
      text: document.body.innerText,
      readme_tables: document.querySelectorAll("#model table").length,
      variables: [...document.querySelectorAll("table.variables tbody tr")].map((row) =>
        [...row.cells].map((cell) => cell.innerText.trim())),
      links: [...document.querySelectorAll("[href], [src]")].map((e) => e.getAttribute("href") ?? e.getAttribute("src")),
      fragment_targets: [...document.querySelectorAll("[id]")].map((e) => e.id),
      scrolls_sideways: document.documentElement.scrollWidth > document.documentElement.clientWidth,
    }));
    seen.unresolved_links = seen.links.filter((link) => !resolves(link, page_url, folder, seen.fragment_targets));
    seen.outside_requests = outside_requests;
    seen.console_errors = console_errors;
    await page.screenshot({ path: screenshot });
    process.stdout.write(JSON.stringify(seen));
  } finally {
    await browser.close();
  }
}

// A fragment must name an element of the page; anything else must be a file inside the archive.
function resolves(link, page_url, folder, fragment_targets) {
  if (link.startsWith("#")) return fragment_targets.includes(decodeURIComponent(link.slice(1)));
  const url = new URL(link, page_url);
  if (url.protocol !== "file:") return false;
  const file = fileURLToPath(url);
  return file.startsWith(folder + path.sep) && fs.existsSync(file);
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
