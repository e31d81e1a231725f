"""`crane-cosim sweep collect`: results.parquet read with pyarrow against results.csv, value for
value, and the summary plots' file names.

The study (tests/sweep/study.json) has eight short closed-loop cases over two parameters and
three metrics, one of which (a window past the end) no case has: its column is all nulls.
"""
import csv
import json
import math
import pathlib
import subprocess

import pyarrow
import pyarrow.parquet
import pytest

STUDY = pathlib.Path(__file__).resolve().parent / "sweep" / "study.json"
PARAMETERS = ["crane.lp0", "pendulum.theta_x0"]
METRICS = ["pendulum.theta_x.rms", "rmse", "pendulum.theta_y.max"]


def sweep(master, *args):
    return subprocess.run([str(master), "sweep", *map(str, args)], check=True, capture_output=True, text=True).stdout


def read_csv(file):
    with open(file, newline="") as f:
        return list(csv.DictReader(f))


def number(cell):
    return None if cell == "" else float(cell)


def test_parquet_holds_the_csv_rows_with_typed_columns_and_nulls(master, tmp_path):
    out = tmp_path / "out"
    sweep(master, "run", STUDY, "-o", out, "--shard", "0/2", "--jobs", "2", "--quiet")
    printed = sweep(master, "collect", out)
    assert printed.splitlines()[-1].endswith("results.csv: 4 done, 0 failed, 4 pending"), printed
    check_parquet_against_csv(out, done={0, 2, 4, 6})

    sweep(master, "run", STUDY, "-o", out, "--jobs", "2", "--quiet")
    # Jobs running side by side each rewrite the manifest: the last may predate others' cases.
    manifest = json.loads((out / "manifest.json").read_text())
    stale = {**manifest, "cases": [{**case, "status": "pending"} for case in manifest["cases"]]}
    (out / "manifest.json").write_text(json.dumps(stale))
    sweep(master, "collect", out)
    check_parquet_against_csv(out, done=set(range(8)))
    refreshed = json.loads((out / "manifest.json").read_text())
    assert [case["status"] for case in refreshed["cases"]] == ["done"] * 8


def check_parquet_against_csv(out, done):
    rows = read_csv(out / "results.csv")
    table = pyarrow.parquet.read_table(out / "results.parquet")
    columns = ["case", "index", "seed", "status", *PARAMETERS, *METRICS, "wall_time"]
    assert table.column_names == columns
    types = [pyarrow.string(), pyarrow.int64(), pyarrow.uint64(), pyarrow.string()] + [pyarrow.float64()] * 6
    assert [field.type for field in table.schema] == types
    records = table.to_pylist()
    assert len(records) == len(rows) == 8
    for index, (record, row) in enumerate(zip(records, rows)):
        assert (record["case"], record["index"], record["status"]) == (row["case"], index, row["status"])
        assert record["seed"] == int(row["seed"])
        for name in PARAMETERS + METRICS:
            assert record[name] == number(row[name]), (index, name)
        assert record["status"] == ("done" if index in done else "pending")
        if index in done:
            assert record["wall_time"] > 0 and not math.isnan(record["rmse"])
            assert record["pendulum.theta_y.max"] is None
        else:
            assert record["wall_time"] is None and record["crane.lp0"] is None
    # The plan's seeds use all 64 bits: at least one is above the largest int64.
    assert max(r["seed"] for r in records) > 2**63 - 1


def test_collect_draws_a_scatter_per_metric_and_parameter_and_a_histogram_per_metric(master, tmp_path):
    out = tmp_path / "out"
    sweep(master, "run", STUDY, "-o", out, "--jobs", "2", "--quiet")
    printed = sweep(master, "collect", out, "--plots", "svg")
    # The window of pendulum.theta_y.max holds no sample: no plot of it.
    expected = sorted(
        [f"{m}-vs-{p}.svg" for m in METRICS[:2] for p in PARAMETERS] + [f"{m}-histogram.svg" for m in METRICS[:2]]
    )
    assert sorted(f.name for f in (out / "plots").iterdir()) == expected
    assert f"6 plots in {out / 'plots'}" in printed
    scatter = (out / "plots" / "rmse-vs-crane.lp0.svg").read_text()
    assert scatter.count("<circle") == 8, "one point per case"
