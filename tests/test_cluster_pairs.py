"""scripts/cluster-pairs --quick: alternating pairs of configuration (8), every frame checked.

On the emulated cluster as root (as test_newton_table.py), else on a private local PVM.
A renderer that changes pixels must make it fail, naming the run.
"""
import json
import re
import shutil
import subprocess
import sys

import pytest

from fcutil import POVRAY_FC, TOP
from test_newton_table import cluster_usable

CLUSTER_PAIRS = TOP / "scripts" / "cluster-pairs"


def run(tmp_path, *extra):
    args = [sys.executable, str(CLUSTER_PAIRS), "--quick", "--pairs", "2", "--out", str(tmp_path / "out"),
            *extra]
    if not cluster_usable():
        args.append("--no-cluster")
    return subprocess.run(args, capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)


def test_pairs_of_the_same_build_report_ratios(tmp_path):
    assert POVRAY_FC.is_file(), "build povray-fc first (make)"
    done = run(tmp_path)
    assert done.returncode == 0, done.stdout + done.stderr
    pairs = re.findall(r"^pair (\d): A ([\d.]+) s, B ([\d.]+) s, A/B ([\d.]+)$", done.stdout, re.M)
    assert [p[0] for p in pairs] == ["1", "2"], done.stdout
    for _, a, b, ratio in pairs:
        a, b, ratio = float(a), float(b), float(ratio)
        # The times are printed to the millisecond: on runs of 0.1 s their quotient may be 1%
        # off the ratio of the unrounded times.
        assert abs(a / b - ratio) <= 0.0006 + ratio * 0.0005 * (1 / a + 1 / b), (a, b, ratio)
    assert "(8) A/B wall over 2 alternating pairs" in done.stdout
    assert "every frame equal to (1)" in done.stdout


def test_a_renderer_that_changes_pixels_fails(tmp_path):
    # The same renderer with another release angle: every frame differs from (1).
    brighter = tmp_path / "brighter"
    brighter.write_text(f"#!/bin/sh\nexec {POVRAY_FC} \"$@\" Declare=Theta0Deg=20\n")
    brighter.chmod(0o755)
    done = run(tmp_path, "--renderer-a", str(brighter))
    assert done.returncode == 1, done.stdout + done.stderr
    assert "(8) A run 1:" in done.stderr and "pixels differ" in done.stderr, done.stderr


@pytest.mark.skipif(shutil.which("perf") is None, reason="perf (linux-perf) is not installed")
def test_cpu_accounting_names_each_program_on_each_processor(tmp_path):
    done = run(tmp_path, "--cpu")
    assert done.returncode == 0, done.stdout + done.stderr
    for side in ("A", "B"):
        head = re.search(rf"^\(8\) {side}: CPU per run, median over 2 runs .*window (\d+) ms", done.stdout, re.M)
        assert head, done.stdout
        lines = re.findall(rf"^\(8\) {side}: CPU per run.*\n((?:  processor .*\n)+)", done.stdout, re.M)
        assert lines, done.stdout
        busy_total = 0
        programs = set()
        for line in lines[0].splitlines():
            m = re.match(r"  processor \d+: busy (\d+) ms, idle (\d+) ms: (.*)$", line)
            assert m, line
            busy, idle = int(m.group(1)), int(m.group(2))
            # Invariant: a processor is busy or idle within the window, never more.
            assert busy + idle <= int(head.group(1)) * 1.1 + 2, line
            busy_total += busy
            programs |= {p.rsplit(" ", 1)[0] for p in m.group(3).split(", ") if p}
        # The renderers, the slaves and the master all ran, and took time.
        assert {"povray-fc", "fc-slave", "fc-master"} <= programs, done.stdout
        assert busy_total > 0
        floor = re.search(rf"^\(8\) {side}: CPU per run.*\n(?:  processor .*\n)+  no idle at all: "
                          rf"(\d+) ms \(all processors' busy time over (\d+)\)$", done.stdout, re.M)
        assert floor, done.stdout
        # Invariant: the work shared out over the processors (the median of two runs is their
        # mean, as is each processor's: equal up to the printed rounding) fits in the window.
        cpus = int(floor.group(2))
        assert cpus == len(lines[0].splitlines())
        assert abs(int(floor.group(1)) - busy_total / cpus) <= 1, done.stdout
        assert int(floor.group(1)) <= int(head.group(1)) * 1.1 + 2, done.stdout


def test_another_ini_and_fewer_frames(tmp_path):
    # The runs render the INI and the number of frames asked for, not newton-table's.
    hd = TOP / "scenes" / "newton" / "newton-hd.ini"
    done = run(tmp_path, "--ini", str(hd), "--frames", "3")
    assert done.returncode == 0, done.stdout + done.stderr
    for side in ("A1", "B1", "A2", "B2"):
        stats = json.loads((tmp_path / "out" / f"c8-{side}" / "stats.json").read_text())
        assert stats["scene"] == str(hd) and stats["frames_rendered"] == 3, stats


@pytest.mark.parametrize("extra,message", [
    (["--frames", "46"], "--frames 46: the INI has 45"),
    (["--ini", "/no/such.ini"], "--ini /no/such.ini: no such file"),
], ids=["frames", "ini"])
def test_bad_ini_or_frames_are_refused(tmp_path, extra, message):
    done = run(tmp_path, *extra)
    assert done.returncode == 2 and message in done.stderr, done.stderr
