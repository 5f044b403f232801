"""scripts/cluster-pairs --quick: alternating pairs of configuration (8), every frame checked.

On the emulated cluster as root (as test_newton_table.py), else on a private local PVM.
A renderer that changes pixels must make it fail, naming the run.
"""
import re
import subprocess
import sys

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
        assert abs(float(a) / float(b) - float(ratio)) < 0.01
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
