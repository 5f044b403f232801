"""scripts/results-table: the README's one results table is what the measurement scripts wrote.

`make test`'s fast tier runs `results-table --check` on the checkout; these tests show that
the check passes on a table rebuilt from the files, fails on a tampered one, and that rows
follow the files (a missing file says "not measured yet")."""
import csv
import json
import shutil
import subprocess

from fcutil import TOP

SCRIPT = TOP / "scripts" / "results-table"
README = "intro\n\n<!-- results-table begin -->\n<!-- results-table end -->\n\nafter\n"


def run(*args):
    return subprocess.run(["/usr/bin/python3", str(SCRIPT), *map(str, args)],
                          capture_output=True, text=True, timeout=60)


def copy_docs(tmp_path):
    docs = tmp_path / "docs"
    docs.mkdir()
    for name in ("fc-goals.json", "newton-table.csv", "newton-table.md"):
        shutil.copy(TOP / "docs" / name, docs / name)
    readme = tmp_path / "README.md"
    readme.write_text(README)
    return docs, readme


def table_of(readme):
    text = readme.read_text()
    return text[text.index("begin -->"):text.index("<!-- results-table end")]


def test_the_checkout_table_matches_its_docs():
    r = run("--check")
    assert r.returncode == 0, r.stderr


def test_a_rebuilt_table_passes_and_a_tampered_one_fails(tmp_path):
    docs, readme = copy_docs(tmp_path)
    assert run("--check", "--docs", docs, "--readme", readme).returncode != 0
    r = run("--docs", docs, "--readme", readme)
    assert r.returncode == 0, r.stderr
    assert readme.read_text().startswith("intro\n") and readme.read_text().endswith("\nafter\n")
    assert run("--check", "--docs", docs, "--readme", readme).returncode == 0
    ours = [row["total_ratio"] for row in csv.DictReader(open(docs / "newton-table.csv"))
            if row["config"] == "8"][0]
    figure = f"{float(ours):.3f}"
    assert f"| {figure} (" in table_of(readme)
    readme.write_text(readme.read_text().replace(f"| {figure} (", "| 0.140 (", 1))
    r = run("--check", "--docs", docs, "--readme", readme)
    assert r.returncode == 1
    assert "differs" in r.stderr and str(readme) in r.stderr


def test_a_changed_measurement_fails_the_check_until_rebuilt(tmp_path):
    docs, readme = copy_docs(tmp_path)
    run("--docs", docs, "--readme", readme)
    report = json.loads((docs / "fc-goals.json").read_text())
    report["g1"][0]["first"] = 1.05
    (docs / "fc-goals.json").write_text(json.dumps(report))
    assert run("--check", "--docs", docs, "--readme", readme).returncode == 1
    run("--docs", docs, "--readme", readme)
    assert "| 1.05x (met) |" in table_of(readme)


def test_missing_files_say_not_measured_and_present_ones_give_rows(tmp_path):
    docs, readme = copy_docs(tmp_path)
    run("--docs", docs, "--readme", readme)
    assert table_of(readme).count("not measured yet") == 3
    with open(docs / "liveness-goals.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["scenario", "measured_s", "goal_s", "met", "note"])
        w.writeheader()
        w.writerow({"scenario": "stopped-pvmd", "measured_s": "3.0", "goal_s": "10.0", "met": "yes", "note": ""})
        w.writerow({"scenario": "stopped-pvmd", "measured_s": "12.5", "goal_s": "10.0", "met": "NO", "note": ""})
        # goals of their own per run: paired run by run
        w.writerow({"scenario": "stopped-slave", "measured_s": "82.2", "goal_s": "109.5", "met": "yes", "note": ""})
        w.writerow({"scenario": "stopped-slave", "measured_s": "107.4", "goal_s": "121.4", "met": "yes", "note": ""})
    fields = ["animation", "size", "frames", "changed_share", "traced_share", "changed", "traced",
              "ratio", "rays", "full_frames", "paused_frames", "followable", "reasons", "differ"]
    with open(docs / "fc-precision.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for name, ratio in (("clockd", 1.5), ("fc-tests/fog", 1.1), ("fc-tests/fly_out", 3.0)):
            w.writerow(dict.fromkeys(fields, "0") | {"animation": name, "size": "160x120", "changed": "10",
                                                      "ratio": str(ratio), "followable": "True"})
    memory = ["config", "budget_mib", "store_mib", "store_bytes_per_pixel", "peak_rss_mib", "wall_s",
              "traced_after_first", "over_budget_blocks", "differ"]
    with open(docs / "fc-memory.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=memory)
        w.writeheader()
        w.writerow(dict.fromkeys(memory, "0") | {"config": "on", "budget_mib": "", "store_mib": "2048.0",
                                                  "store_bytes_per_pixel": "1035", "traced_after_first": "900"})
        w.writerow(dict.fromkeys(memory, "0") | {"config": "budget", "budget_mib": "512", "store_mib": "511.5",
                                                  "traced_after_first": "5000"})
    assert run("--check", "--docs", docs, "--readme", readme).returncode == 1
    run("--docs", docs, "--readme", readme)
    table = table_of(readme)
    assert "not measured yet" not in table
    assert "| worst 12.5 s (missed) | <= 10.0 s |" in table
    assert "| 82.2 / 107.4 s (met) | <= 109.5 / 121.4 s, run by run |" in table
    assert "median 1.50x (met), worst 1.50x (met) (clockd)" in table
    assert "median 2.05x (missed), worst 3.00x (met) (fc-tests/fly_out)" in table
    assert "| 2.000 GiB (missed), 1035 B/pixel |" in table
    assert "store 511.5 MiB (within the budget), 5000 pixels traced after frame 1 (without a budget 900)" in table


def test_a_readme_without_markers_is_a_clear_error(tmp_path):
    docs, readme = copy_docs(tmp_path)
    readme.write_text("no markers\n")
    r = run("--check", "--docs", docs, "--readme", readme)
    assert r.returncode != 0 and "README.md" in r.stderr and "results-table begin" in r.stderr
