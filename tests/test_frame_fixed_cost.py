"""scripts/frame-fixed-cost end to end on a few frames: every configuration delivers all its
frames and reports a cost; fc on, as a slave runs it, reuses the block fc off traces."""
import re
import subprocess
import sys

from fcutil import POVRAY_FC, TOP

FRAME_FIXED_COST = TOP / "scripts" / "frame-fixed-cost"


def run(*args):
    return subprocess.run([sys.executable, str(FRAME_FIXED_COST), *args], capture_output=True,
                          text=True, timeout=120, stdin=subprocess.DEVNULL)


def test_frame_fixed_cost_reports_every_configuration(tmp_path):
    assert POVRAY_FC.is_file(), "build povray-fc first (make)"
    done = run("--frames", "6", "--stock-frames", "1", "--repeat", "1", "--out", str(tmp_path))
    assert done.returncode == 0, done.stdout + done.stderr
    rows = {}
    for line in done.stdout.splitlines():
        m = re.match(r"(slave, fc on|slave, fc off|single, fc on|single, fc off|stock povray)"
                     r"\s+(\d+)\s+([\d.]+) \(", line)
        if m:
            rows[m.group(1)] = (int(m.group(2)), float(m.group(3)))
    assert set(rows) == {"slave, fc on", "slave, fc off", "single, fc on", "single, fc off",
                         "stock povray"}, done.stdout
    assert rows["slave, fc on"][0] == 6 and rows["stock povray"][0] == 1
    assert all(cpu_ms > 0 for _, cpu_ms in rows.values()), rows
    # The slave's channel carried a record per frame (the script checks and fails otherwise),
    # and with fc on frames 2-6 reused the pixel's block: its rays say so.
    channel = (tmp_path / "slave-fc-on" / "channel.bin").read_bytes()
    rays = [int(r) for r in re.findall(rb"FCFRAME 1 frame=\d+ rays=(\d+)", channel)]
    assert len(rays) == 6 and rays[0] > 0 and rays[1:] == [0] * 5, rays


def test_frame_fixed_cost_rejects_bad_options(tmp_path):
    done = run("--repeat", "0", "--out", str(tmp_path))
    assert done.returncode != 0 and "--repeat 0" in done.stderr
    done = run("--frames", "1", "--out", str(tmp_path))
    assert done.returncode != 0 and "--frames 1: must be at least 2" in done.stderr
    done = run("--stock", str(tmp_path / "no-povray"), "--out", str(tmp_path))
    assert done.returncode != 0 and "no-povray: no such file" in done.stderr
