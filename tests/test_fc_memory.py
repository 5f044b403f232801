"""scripts/fc-memory: the store's size and a budget's cost, on a tiny render of its scene."""
import csv
import subprocess
from pathlib import Path

TOP = Path(__file__).resolve().parent.parent
FC_MEMORY = TOP / "scripts" / "fc-memory"


def test_a_tiny_budget_keeps_the_store_within_it_and_every_frame_exact(tmp_path):
    table = tmp_path / "memory.csv"
    done = subprocess.run(["/usr/bin/python3", str(FC_MEMORY), "--size", "96x54", "--budget", "1",
                           "--out", str(tmp_path / "work"), "--csv", str(table)],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    with open(table, newline="") as f:
        rows = {r["config"]: r for r in csv.DictReader(f)}
    assert set(rows) == {"off", "on", "budget"}
    assert all(r["differ"] == "0" for r in rows.values())
    # Without a budget the store holds more than 1 MiB; with one it keeps within it, and the
    # blocks it left out are traced again in the second frame.
    assert float(rows["on"]["store_mib"]) > 1.0
    assert float(rows["budget"]["store_mib"]) <= 1.0
    assert int(rows["budget"]["over_budget_blocks"]) > 0
    assert int(rows["budget"]["traced_after_first"]) > int(rows["on"]["traced_after_first"])


def test_a_bad_size_is_a_one_line_error():
    done = subprocess.run(["/usr/bin/python3", str(FC_MEMORY), "--size", "wide"], capture_output=True, text=True)
    assert done.returncode != 0
    assert "--size wide" in done.stderr
