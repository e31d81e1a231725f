"""`crane-cosim run -o results.parquet`: the same values as the CSV of the same run, read with
pyarrow (and pandas where installed), and the units in the file's key-value metadata (`units`, a
JSON object from column name to unit)."""
import csv
import json
import subprocess

import pyarrow.parquet
import pytest

from conftest import fmu_path


def run(master, tmp_path):
    for name in ("r.csv", "r.parquet"):
        args = [str(master), "run", str(fmu_path("pendulum")), "--stop-time", "1", "-q", "-o", str(tmp_path / name)]
        subprocess.run(args, check=True)
    with open(tmp_path / "r.csv", newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(cell) for cell in row] for row in rows[1:]]


def test_parquet_results_hold_the_csv_values_and_the_units(master, tmp_path):
    header, rows = run(master, tmp_path)
    table = pyarrow.parquet.read_table(tmp_path / "r.parquet")
    assert table.column_names == header
    assert table.num_rows == len(rows) == 101
    columns = table.to_pydict()
    assert [[columns[name][i] for name in header] for i in range(len(rows))] == rows
    units = json.loads(pyarrow.parquet.read_schema(tmp_path / "r.parquet").metadata[b"units"])
    assert units["time"] == "s"
    assert units["pendulum.theta_x"] == "rad"
    assert units["pendulum.load.z"] == "m"


def test_pandas_reads_the_parquet_results(master, tmp_path):
    pandas = pytest.importorskip("pandas")
    header, rows = run(master, tmp_path)
    frame = pandas.read_parquet(tmp_path / "r.parquet")
    assert list(frame.columns) == header
    assert frame.to_numpy().tolist() == rows
