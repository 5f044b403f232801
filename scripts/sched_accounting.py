"""Each processor's time during one fc-master run, process by process, from the kernel's
context switches (`perf record -a -e sched:sched_switch`, read back with `perf sched
timehist`): exact CPU time, not perf's samples, and idle time as what no process used.

Used by scripts/cluster-pairs --cpu. A recording covers more than the run (perf starts
first and stops after): the run's window is fc-master's lifetime, from the first to the last
time the kernel switched it out; a process's time is summed over the switches in that
window (a slice that began before the window counts whole: a few ms at most).
"""
import re
import signal
import statistics
import subprocess
import time
from collections import Counter
from pathlib import Path

# perf sched timehist: "time [cpu] command[tid/pid] wait sch-delay run" (milliseconds)
ROW = re.compile(r"\s*([\d.]+)\s+\[(\d+)\]\s+(.*?)\[(\d+)(?:/(\d+))?\]\s+([\d.]+)\s+([\d.]+)\s+([\d.]+)\s*$")
IDLE = ("<idle>", "swapper")


class Recording:
    """perf recording every processor's context switches, from start() until stop()."""

    def __init__(self, path):
        self.path = Path(path)
        self.proc = None

    def start(self):
        self.path.unlink(missing_ok=True)
        try:
            self.proc = subprocess.Popen(["perf", "record", "-q", "-a", "-e", "sched:sched_switch",
                                          "-o", str(self.path)],
                                         stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                         stderr=subprocess.PIPE, text=True)
        except FileNotFoundError:
            raise RuntimeError("--cpu needs perf (Debian package linux-perf)") from None
        # perf writes its file's header once its events are open on every processor.
        deadline = time.monotonic() + 10
        while not (self.path.exists() and self.path.stat().st_size > 0):
            if self.proc.poll() is not None:
                raise RuntimeError("perf record failed: " + self.proc.stderr.read().strip()[-500:])
            if time.monotonic() > deadline:
                self.stop()
                raise RuntimeError("perf record did not start within 10 s")
            time.sleep(0.02)
        time.sleep(0.05)

    def stop(self):
        if self.proc and self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
            try:
                self.proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.proc = None


def account_during(path, run):
    """run() while a Recording at path records: (what run returned, account(path)); the
    recording is removed either way."""
    path = Path(path)
    recording = Recording(path)
    recording.start()
    try:
        result = run()
    finally:
        recording.stop()
    try:
        return result, account(path)
    finally:
        path.unlink(missing_ok=True)


def account(path):
    """{"window": ms, "busy": {cpu: ms}, "idle": {cpu: ms}, "commands": {(cpu, command): ms}}
    of fc-master's lifetime in the recording at path (a command is a process's name: every
    thread of a program counts under it)."""
    out = subprocess.run(["perf", "sched", "timehist", "-i", str(path)], capture_output=True,
                         text=True, stdin=subprocess.DEVNULL)
    if out.returncode != 0:
        raise RuntimeError("perf sched timehist failed: " + out.stderr.strip()[-500:])
    rows = []
    for line in out.stdout.splitlines():
        m = ROW.match(line)
        if m:
            rows.append((float(m.group(1)), int(m.group(2)), m.group(3).strip(), float(m.group(8))))
    master = [t for t, _, comm, _ in rows if comm.startswith("fc-master")]
    if not master:
        raise RuntimeError(f"{path}: fc-master never ran while perf recorded")
    first, last = min(master), max(master)
    cpus = sorted({cpu for _, cpu, _, _ in rows})
    commands = Counter()
    for t, cpu, comm, run in rows:
        if first <= t <= last and not comm.startswith(IDLE):
            commands[(cpu, comm)] += run
    window = (last - first) * 1000.0
    busy = {cpu: sum(v for (c, _), v in commands.items() if c == cpu) for cpu in cpus}
    return {"window": window, "busy": busy, "idle": {cpu: max(0.0, window - busy[cpu]) for cpu in cpus},
            "commands": dict(commands)}


def median_report(runs, least_ms=1.0):
    """One line per processor: the median over runs of its busy and idle time and of each
    command's time (a command missing from a run counts 0 there; commands under least_ms
    left out); then the median of the window the run would take with no idle at all."""
    cpus = sorted({cpu for r in runs for cpu in r["busy"]})
    keys = sorted({k for r in runs for k in r["commands"]})
    lines = []
    for cpu in cpus:
        busy = statistics.median(r["busy"].get(cpu, 0.0) for r in runs)
        idle = statistics.median(r["idle"].get(cpu, 0.0) for r in runs)
        parts = []
        for c, name in keys:
            if c != cpu:
                continue
            ms = statistics.median(r["commands"].get((c, name), 0.0) for r in runs)
            if ms >= least_ms:
                parts.append((ms, name))
        parts.sort(reverse=True)
        lines.append(f"processor {cpu}: busy {busy:.0f} ms, idle {idle:.0f} ms: " +
                     ", ".join(f"{name} {ms:.0f}" for ms, name in parts))
    # The work alone bounds the run: with no processor ever idle it would still take the
    # busy time shared out (what (9) can reach without less work; README, Newton section).
    floor = statistics.median(sum(r["busy"].values()) / len(cpus) for r in runs)
    lines.append(f"no idle at all: {floor:.0f} ms (all processors' busy time over {len(cpus)})")
    return lines
