"""What fc-master tells the user: the progress display, the end summary and --stats.

On a terminal the display fits its width and redraws in place (checked with a small terminal
emulator that records any line the terminal would have to wrap); progress counts only the work
of this run; the summary and the statistics say what happened (frame times, what frame
coherence saved, frames resumed, retried and lost, the error of a failed run).
"""
import fcntl
import os
import pty
import re
import select
import struct
import subprocess
import termios
import time

import pytest

from conftest import (COORDINATOR_SCENES, coordinator_renderer, coordinator_stats,
                      master_with_failing_image_writer)

pytestmark = pytest.mark.usefixtures("coordinator_build")

SCENE = "moving.pov"
SLOW = ["+FT", "+W320", "+H240", "+KFI1", "+KFF16", "+A0.1", "+AM2", "+R3"]


class Terminal:
    """Just enough of a terminal: printable characters, CR, LF, ESC[K, ESC[J, ESC[nA.
    Records whether any character landed in the last column (where it would wrap)."""

    def __init__(self, columns, rows=24):
        self.columns, self.rows = columns, rows
        self.screen = [""]
        self.row = self.col = 0
        self.wrapped = []

    def line(self):
        while len(self.screen) <= self.row:
            self.screen.append("")
        return self.screen[self.row]

    def put(self, ch):
        text = self.line().ljust(self.col)
        self.screen[self.row] = text[:self.col] + ch + text[self.col + 1:]
        self.col += 1
        if self.col >= self.columns:
            self.wrapped.append(self.screen[self.row])
            self.col = 0
            self.row += 1

    def feed(self, data):
        i = 0
        while i < len(data):
            c = data[i]
            if c == "\x1b":
                m = re.match(r"\x1b\[(\d*)([A-Za-z])", data[i:])
                assert m, "unknown escape %r" % data[i:i + 8]
                n, code = int(m.group(1) or 1), m.group(2)
                if code == "A":
                    self.row = max(0, self.row - n)
                elif code == "K":
                    self.screen[self.row] = self.line()[:self.col]
                elif code == "J":
                    self.screen[self.row] = self.line()[:self.col]
                    del self.screen[self.row + 1:]
                else:
                    raise AssertionError("unexpected escape %r" % m.group(0))
                i += len(m.group(0))
                continue
            if c == "\r":
                self.col = 0
            elif c == "\n":
                self.row += 1
                self.col = 0
                self.line()
            else:
                self.put(c)
            i += 1


def run_on_terminal(coordinator, args, columns, env=None, timeout=120, **argv_options):
    """Run fc-master with stderr on a pseudo-terminal of `columns` x 24; returns (exit status,
    everything it wrote there). argv_options go to coordinator.argv (master=, another copy)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, columns, 0, 0))
    p = subprocess.Popen(coordinator.argv(args, **argv_options), cwd=COORDINATOR_SCENES, env=coordinator.env(env), stdin=subprocess.DEVNULL,
                         stdout=subprocess.DEVNULL, stderr=slave)
    coordinator.procs.append(p)
    os.close(slave)
    chunks = []
    deadline = time.time() + timeout
    while time.time() < deadline:
        ready, _, _ = select.select([master], [], [], 0.2)
        if ready:
            try:
                data = os.read(master, 65536)
            except OSError:
                break
            if not data:
                break
            chunks.append(data)
        elif p.poll() is not None:
            break
    os.close(master)
    p.wait(timeout=30)
    return p.returncode, b"".join(chunks).decode(errors="replace")


@pytest.mark.parametrize("columns", [80, 60])
def test_live_display_fits_the_terminal(coordinator, tmp_path, columns):
    rc, text = run_on_terminal(coordinator, ["--no-fc", "--division", "frame", "--slaves", "2",
                                             SCENE] + SLOW + ["-o", str(tmp_path / "out")],
                               columns)
    assert rc == 0, text
    term = Terminal(columns)
    term.feed(text.replace("\r\n", "\n"))
    # Invariant: no line of the display reaches the last column (it would wrap and scroll).
    # (The summary after it is ordinary output and may wrap.)
    display = [w for w in term.wrapped if re.search(r"ETA|in flight|\d busy  \d", w)]
    assert display == [], display
    # It was shown (redrawn in place: the bar is not left on the final screen) ...
    assert "ETA" in text and "in flight" in text and "px/s" in text, text
    assert not any("ETA" in line for line in term.screen), term.screen
    # ... and it never claimed completion before the end; the summary did.
    assert "100%" not in text
    assert any("16 frame(s) rendered" in line for line in term.screen), term.screen


def test_warning_during_the_run_starts_its_own_line(coordinator, tmp_path):
    # fc-image-writer fails at the first assembled frame, while the progress line is shown:
    # the warning clears that line first instead of being written onto its end.
    rc, text = run_on_terminal(coordinator, ["--no-fc", "--division", "frame", "--tile", "80",
                                             "--slaves", "2", SCENE] + SLOW +
                               ["-o", str(tmp_path / "out")], 80,
                               master=master_with_failing_image_writer(tmp_path))
    assert rc == 0, text
    before = text[:text.index("encoding Targa frames with OpenImageIO")]
    assert "ETA" in before, "no progress line before the warning: the test shows nothing\n" + text
    # Where the warning begins the terminal's cursor is at the start of an empty line.
    start = before.rindex("fc-master: warning: ")
    term = Terminal(80)
    term.feed(text[:start].replace("\r\n", "\n"))
    assert term.col == 0 and term.line() == "", (term.line(), text[start - 200:start + 200])


def test_progress_counts_only_this_run(coordinator, tmp_path):
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", SCENE] + SLOW + ["+SF1", "+EF8", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    r = coordinator.run(["--no-fc", "--progress", "0.2", "--slaves", "2", SCENE] + SLOW +
                        ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    lines = [l for l in r.stderr.splitlines() if " frames (" in l]
    assert lines, r.stderr
    for line in lines:
        # Invariant: the 8 frames already there are neither done work nor work to do.
        m = re.search(r"(\d+)/(\d+) frames \((\d+)%\)", line)
        assert m and int(m.group(2)) == 8, line
        assert int(m.group(1)) < 8 and int(m.group(3)) < 100, line
        assert "8 already there" in line, line
    assert "8 frame(s) rendered, 8 already present" in r.stderr


def flaky_renderer(tmp_path, failures):
    counter = tmp_path / "failures"
    script = tmp_path / "flaky-povray"
    script.write_text(f"""#!/bin/sh
case "$*" in *Frame_Control=*)
  n=$(flock {counter}.lock sh -c 'n=$(cat {counter} 2>/dev/null || echo 0); n=$((n + 1)); echo $n > {counter}; echo $n')
  if [ {failures} -lt 0 ] || [ "$n" -le {failures} ]; then echo "simulated host failure" >&2; exit 3; fi
esac
exec {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    return script


def test_summary_and_stats_of_a_run(coordinator, tmp_path):
    out, stats = tmp_path / "out", tmp_path / "stats.json"
    script = flaky_renderer(tmp_path, 1)
    r = coordinator.run(["--povray", str(script), "--division", "sequence", "--slaves", "2",
                         "--stats", str(stats), SCENE] + SLOW + ["-o", str(out)],
                        renderer=False)
    assert r.returncode == 0, r.stderr
    s = coordinator_stats(stats)
    # A failed job's frame ran again: counted, none lost, no error.
    assert s["frames_retried"] >= 1 and s["frames_lost"] == 0 and s["error"] is None, s
    assert sum(f["retried"] for f in s["frames"]) == s["frames_retried"]
    assert "retried" in r.stderr
    # Per-frame times, and what frame coherence saved (estimated from the first frames).
    assert all(f["time"] > 0 for f in s["frames"])
    assert re.search(r"frame time: median [\d.]+ s.*slowest [\d.]+ s \(frame \d+\)", r.stderr)
    # The summary fits a terminal of 80 columns.
    lines = r.stderr.splitlines()
    start = next(i for i, line in enumerate(lines) if "frame(s) rendered" in line)
    assert all(len(line) < 80 for line in lines[start:]), "\n".join(lines[start:])
    saved = s["fc_saved"]
    assert saved and saved["rays_without_fc"] > saved["rays_spent"] > 0, saved
    assert "frame coherence saved about" in r.stderr, r.stderr
    assert all(h["pixels"] > 0 for h in s["hosts"]) and "px/s" in r.stderr


def test_stats_of_a_failed_run_keep_the_error(coordinator, tmp_path):
    out, stats = tmp_path / "out", tmp_path / "stats.json"
    r = coordinator.run(["--no-fc", "--division", "sequence", "--slaves", "2", "--stats",
                         str(stats), "fails-late.pov", "+FT", "+W64", "+H48", "+KFI1", "+KFF8", "-o",
                         str(out)])
    assert r.returncode == 1
    s = coordinator_stats(stats)
    # Invariant: a failed run's statistics hold its error and what is missing.
    assert not s["success"] and "deliberate failure" in s["error"], s["error"]
    assert s["frames_lost"] == 8 - s["frames_rendered"] > 0
    assert re.search(r"failed with \d+ of 8 frame\(s\) done", r.stderr), r.stderr
