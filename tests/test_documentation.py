"""Every FMU's documentation/index.html as a reader sees it: opened from the unpacked archive in
headless Chromium (playwright-core, tests/documentation/inspect.cjs), it must name the model,
its FMI version, GUID and generation tool and date, render the README's headings and tables
(no Markdown left as text), list every variable with its unit, fit the window without scrolling
sideways and have no link that leaves the archive. A screenshot of each page's first screen is
kept in target/documentation/<model>.png.

`cargo xtask test` installs Chromium and playwright-core (into target/documentation-check)."""
import json
import os
import re
import shutil
import subprocess
import zipfile

import pytest
from fmpy import read_model_description

from conftest import ROOT, fmu_entry, fmu_names, fmu_path

MODELS = fmu_names()
NODE_MODULES = ROOT / "target" / "documentation-check" / "node_modules"
SCREENSHOTS = ROOT / "target" / "documentation"


def inspect(name, folder):
    """What inspect.cjs saw on the unpacked FMU's page (and the screenshot's path)."""
    if not (NODE_MODULES / "playwright-core").exists():
        pytest.fail(f"{NODE_MODULES}/playwright-core is missing: `cargo xtask test` installs it")
    node = shutil.which("node") or pytest.fail("node is missing: `cargo xtask test` installs npm and Node.js")
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    screenshot = SCREENSHOTS / f"{name}.png"
    screenshot.unlink(missing_ok=True)
    done = subprocess.run([node, str(ROOT / "tests" / "documentation" / "inspect.cjs"), str(folder), str(screenshot)],
                          capture_output=True, text=True, timeout=120, env=dict(os.environ, NODE_PATH=str(NODE_MODULES)))
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout), screenshot


def readme_headings(name):
    """The `##` headings of the model's README, as text (inline code marks removed)."""
    lines = (ROOT / fmu_entry(name)["readme"]).read_text().splitlines()
    return [line[3:].replace("`", "").strip() for line in lines if line.startswith("## ")]


def readme_table_count(name):
    """Markdown tables in the model's README, also those indented in a list item: one delimiter row (`|---|` or
    `| :-- |`) each."""
    text = (ROOT / fmu_entry(name)["readme"]).read_text()
    return len(re.findall(r"^[ \t]*\|\s*:?-{3,}", text, flags=re.MULTILINE))


@pytest.mark.parametrize("name", MODELS)
def test_documentation_page_in_chromium(name, tmp_path):
    zipfile.ZipFile(fmu_path(name)).extractall(tmp_path)
    md = read_model_description(str(fmu_path(name)))
    seen, screenshot = inspect(name, tmp_path)
    text = seen["text"]

    assert seen["h1"] == [md.modelName] and md.modelName in seen["title"]
    for fact in (f"FMI version\t{md.fmiVersion} (Co-Simulation)", f"GUID\t{md.guid}",
                 f"Generation tool\t{md.generationTool}", "Platforms\t" + ", ".join(fmu_entry(name)["platforms"])):
        assert fact in text, fact
    assert re.search(r"Generation date\t\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ", text)
    # The README rendered: its sections are headings, its tables tables, no Markdown left over.
    assert set(readme_headings(name)) <= set(seen["headings"]), (readme_headings(name), seen["headings"])
    assert seen["readme_tables"] == readme_table_count(name)
    assert "**" not in text and "\n## " not in text and "|---" not in text
    # Every variable, with its unit, in model-description order.
    rows = {row[0]: row for row in seen["variables"]}
    assert list(rows) == [v.name for v in md.modelVariables]
    with_unit = [v for v in md.modelVariables if v.unit]
    assert with_unit and all(rows[v.name][5] == v.unit for v in with_unit)
    assert seen["links"] and not seen["unresolved_links"], seen["unresolved_links"]
    assert not seen["outside_requests"] and not seen["console_errors"]
    assert not seen["scrolls_sideways"]
    assert screenshot.stat().st_size > 10_000
    print(f"{name}: documentation with {len(seen['headings'])} headings, {seen['readme_tables']} README tables, "
          f"{len(rows)} variables ({len(with_unit)} with units), {len(seen['links'])} links resolved; "
          f"screenshot {screenshot}")
