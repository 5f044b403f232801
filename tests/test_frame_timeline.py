"""scripts/frame-timeline: who held up each frame of an fc-master run, from its protocol trace.

One test reads a trace written by hand, whose answers are worked out below; the other reads
the trace of a real frame division, where every frame's parts must add up to all its tiles."""
import re
import subprocess
import sys

from fcutil import TOP

FRAME_TIMELINE = TOP / "scripts" / "frame-timeline"
SCENE = "moving.pov"


def timeline(log, *args):
    return subprocess.run([sys.executable, str(FRAME_TIMELINE), *args, str(log)],
                          capture_output=True, text=True, timeout=60, stdin=subprocess.DEVNULL)


def rows(out):
    """frame -> [(slave column, ms, tiles, last)] from the table's lines."""
    lines = out.splitlines()
    names = lines[0].split()[1:-5]      # "frame  tA  tB   (ms sent, tiles; * last)"
    table = {}
    for line in lines[1:]:
        if not line.strip():
            break
        frame, rest = line.split(None, 1)
        cells = re.findall(r"(\d+)\s+(\d+)(\*?)|(-)", rest)
        parts = []
        for name, (ms, tiles, star, dash) in zip(names, cells):
            if not dash:
                parts.append((name, int(ms), int(tiles), star == "*"))
        table[int(frame)] = parts
    return table


# Two slaves (pids 11 and 12, tasks t40002 and t80002). Frame 1: both get it at once, the
# second sends 30 ms after the first; frame 2: the first slave waits 20 ms for its job;
# frame 3: the second slave's first job for it is cancelled before it began, and it waits 10
# ms for the next.
HAND_TRACE = """\
100.000 fc-master[10] master starts
100.010 fc-master[10] FC_JOB 1 frame 1, 2 tile(s) to t40002
100.010 fc-master[10] FC_JOB 2 frame 1, 1 tile(s) to t80002
100.011 fc-slave[11] job 1: frame 1, 2 tile(s)
100.011 fc-slave[12] job 2: frame 1, 1 tile(s)
100.020 fc-slave[11] sent frame 1 of job 1
100.050 fc-slave[12] sent frame 1 of job 2
100.040 fc-master[10] FC_JOB 3 frame 2, 2 tile(s) to t40002
100.040 fc-slave[11] job 3: frame 2, 2 tile(s)
100.050 fc-master[10] FC_JOB 4 frame 2, 1 tile(s) to t80002
100.051 fc-slave[12] job 4: frame 2, 1 tile(s)
100.060 fc-slave[12] sent frame 2 of job 4
100.070 fc-slave[11] sent frame 2 of job 3
100.061 fc-master[10] FC_JOB 5 frame 3, 1 tile(s) to t80002
100.061 fc-slave[12] job 5: frame 3, 1 tile(s)
100.065 fc-slave[12] job 5 cancelled before it began
100.071 fc-master[10] FC_JOB 7 frame 3, 2 tile(s) to t40002
100.071 fc-slave[11] job 7: frame 3, 2 tile(s)
100.075 fc-master[10] FC_JOB 6 frame 3, 1 tile(s) to t80002
100.075 fc-slave[12] job 6: frame 3, 1 tile(s)
100.080 fc-slave[12] sent frame 3 of job 6
100.090 fc-slave[11] sent frame 3 of job 7
garbage that is not a trace line
"""


def test_frame_timeline_reads_a_trace(tmp_path):
    log = tmp_path / "trace.log"
    log.write_text(HAND_TRACE)
    done = timeline(log)
    assert done.returncode == 0, done.stderr
    table = rows(done.stdout)
    assert table == {1: [("t40002", 20, 2, False), ("t80002", 50, 1, True)],
                     2: [("t40002", 70, 2, True), ("t80002", 60, 1, False)],
                     3: [("t40002", 90, 2, True), ("t80002", 80, 1, False)]}, done.stdout
    # t40002 sent frame 1 at 20 ms and got its next job at 40 ms (a wait of 20 ms), then
    # waited 1 ms at 70; t80002 waited 1 ms twice and, once its cancelled job was dropped at
    # 65 ms, 10 ms for the next, and finished 10 ms before the last part.
    assert re.search(r"^t40002: waited 21 ms .*: 20 ms at 20; done 0 ms", done.stdout, re.M), \
        done.stdout
    assert re.search(r"^t80002: waited 12 ms .*: 10 ms at 65; done 10 ms", done.stdout, re.M), \
        done.stdout


def test_frame_timeline_errors_name_the_file(tmp_path):
    missing = tmp_path / "nothing.log"
    done = timeline(missing)
    assert done.returncode != 0 and str(missing) in done.stderr, done.stderr
    empty = tmp_path / "empty.log"
    empty.write_text("100.000 fc-master[10] master starts\n")
    done = timeline(empty)
    assert done.returncode != 0 and "sent frame" in done.stderr, done.stderr


def test_frame_timeline_of_a_frame_division(coordinator, tmp_path):
    out = tmp_path / "frames"
    # 160x120 in tiles of 40: 12 tiles a frame, over two slaves.
    r = coordinator.run(["--quiet", "--division", "frame", "--tile", "40", "--slaves", "2",
                         SCENE, "+W160", "+H120", "+KFI1", "+KFF6", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    done = timeline(coordinator.debug_log)
    assert done.returncode == 0, done.stderr
    table = rows(done.stdout)
    assert sorted(table) == [1, 2, 3, 4, 5, 6], done.stdout
    for frame, parts in table.items():
        # Every tile is sent once (a straggler's duplicate would add to it: none here, where
        # no slave is slow), exactly one part is marked last, and it is the latest.
        assert sum(tiles for _, _, tiles, _ in parts) == 12, (frame, done.stdout)
        assert [last for *_, last in parts].count(True) == 1, (frame, done.stdout)
        latest = max(parts, key=lambda p: p[1])
        assert latest[3] or any(p[1] == latest[1] and p[3] for p in parts), done.stdout
    slaves = re.findall(r"^(t[0-9a-f]+): waited \d+ ms", done.stdout, re.M)
    assert len(slaves) == 2, done.stdout
