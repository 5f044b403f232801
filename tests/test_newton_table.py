"""scripts/newton-table --quick end to end: Table 1's five configurations on 6 tiny frames.

As root, with network namespaces and sshd, on the emulated cluster (hosts fch1..fch3 of
scripts/pvm-netns-hosts.sh, or other names when another run's hosts are up; set up and torn
down by the script; about 15 s); otherwise with --no-cluster (a private local PVM).
"""
import csv
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from fcutil import POVRAY_FC, TOP

NEWTON_TABLE = TOP / "scripts" / "newton-table"


def cluster_usable():
    if os.geteuid() != 0 or not shutil.which("ip") or not os.path.exists("/usr/sbin/sshd"):
        return False
    if not os.path.exists("/sys/fs/cgroup/cpu/cpu.cfs_quota_us"):
        return False
    # Hosts another run has up do not matter: the script's cluster gets names of its own.
    return subprocess.run(["ip", "netns", "list"], capture_output=True).returncode == 0


def test_newton_table_quick(tmp_path):
    assert POVRAY_FC.is_file(), "build povray-fc first (make)"
    out = tmp_path / "newton-table"
    args = [sys.executable, str(NEWTON_TABLE), "--quick", "--out", str(out)]
    cluster = cluster_usable()
    if not cluster:
        args.append("--no-cluster")
    done = subprocess.run(args, capture_output=True, text=True, timeout=85,
                          stdin=subprocess.DEVNULL)
    assert done.returncode == 0, done.stdout + done.stderr
    # Invariant: every configuration rendered the same frames, and the script says so.
    assert "All five configurations produced identical frames" in done.stdout

    md = (out / "newton-table.md").read_text()
    assert "identical frames" in md
    for column in ("(1) single processor", "(2) single processor with fc",
                   "(4) 3 processors", "(6) 3 processors with fc (seq div)",
                   "(8) 3 processors with fc (frame div)", "(9) ratio of (8) to (1)"):
        assert column in md, column
    assert "21,970,900" in md and "1:55:51" in md      # the paper's figures beside ours
    assert ("namespace hosts" in md) == cluster

    with open(out / "newton-table.csv", newline="") as f:
        rows = {r["config"]: r for r in csv.DictReader(f)}
    assert sorted(rows) == ["1", "2", "4", "6", "8"]
    rays = {k: int(r["rays"]) for k, r in rows.items()}
    # Invariant: frame coherence traces fewer rays than the same work without it.
    assert rays["2"] < rays["1"] and rays["6"] < rays["4"] and rays["8"] < rays["4"]
    # Without fc, tiling adds no rays here (no antialiasing): same work as one processor.
    assert rays["4"] == rays["1"]
    for r in rows.values():
        assert int(r["frames"]) == 6 and r["size"] == "80x60"
        assert float(r["total_s"]) > 0
        assert abs(float(r["average_frame_s"]) * 6 - float(r["total_s"])) < 1e-3
    assert float(rows["1"]["first_frame_s"]) > 0 and float(rows["2"]["first_frame_s"]) > 0
    assert rows["4"]["first_frame_s"] == ""

    # Nothing of the cluster is left behind (other clusters may be up: only its own hosts).
    if cluster:
        up = re.search(r"hosts (\S+) \(1 core\), (\S+), (\S+) \(0\.5 core each\) are up",
                       done.stderr)
        assert up, done.stderr
        hosts = set(up.groups())
        assert f"hosts {' '.join(up.groups())} are down" in done.stderr
        r = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True)
        assert not hosts & {line.split()[0] for line in r.stdout.splitlines() if line.split()}
        assert not hosts & {p.name[len("fc-netns-"):]
                            for p in Path("/sys/fs/cgroup/cpu").glob("fc-netns-*")}
        with open("/etc/hosts") as f:
            assert not hosts & {w for line in f for w in line.split()}
    # Frames are removed after the check unless --keep; stats and logs stay.
    assert not list(out.glob("runs/*/frames"))
    assert (out / "runs" / "c1-r1" / "stats.csv").is_file()
    assert (out / "runs" / "c8-r1" / "stats.json").is_file()
