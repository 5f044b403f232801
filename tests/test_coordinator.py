"""fc-master / fc-slave: distributed rendering over a real PVM virtual machine.

Every test runs the real programs: fc-master starts a private pvmd (or joins one the test
started) and real fc-slave tasks that run the renderer. Frames must be pixel-identical to one
POV-Ray process rendering the same frames. The `coordinator` fixture kills, by pid, whatever
a test leaves behind; tests also assert that nothing was left.
"""
import os
import re
import resource
import signal
import subprocess
import time

import numpy as np
import pytest

from conftest import (COORDINATOR_SCENES, FC_SLAVE, coordinator_cmdline,
                      coordinator_renderer, coordinator_stats, frame_files, load_rgb)

pytestmark = pytest.mark.usefixtures("coordinator_build")

SCENE = "moving.pov"
# Targa, as the single-process references (without a format named, fc-master writes what
# POV-Ray's povray.ini says, as povray-fc does: Debian's says PNG).
# Small frames, few of them: the whole module must stay fast on 2 cores.
SMALL = ["+FT", "+W160", "+H120", "+KFI1", "+KFF8"]
# Slow enough (about 0.2 s per frame per process) to interrupt a render in the middle.
SLOW = ["+FT", "+W320", "+H240", "+KFI1", "+KFF16", "+A0.1", "+AM2", "+R3"]


def assert_same_frames(outdir, reference, only=None, temporary=()):
    """outdir holds exactly the reference's frames (or the subset `only`), pixel for pixel,
    and besides them only the files named in `temporary`."""
    files = frame_files(outdir)
    expected = sorted(reference) if only is None else sorted(only)
    # Invariant: output names are POV-Ray's own, and no temporary file is left over.
    assert files == sorted(expected + list(temporary))
    for name in expected:
        got = load_rgb(os.path.join(outdir, name))
        want = reference[name]
        assert got.shape == want.shape, name
        differing = int(np.any(got != want, axis=2).sum())
        # Invariant: distributed frames equal the single-process render exactly.
        assert differing == 0, "%s: %d pixels differ" % (name, differing)


def wait_for_frames(outdir, count, proc, timeout=60):
    """Wait until outdir holds at least `count` final frames (fails if proc ends first)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        if os.path.isdir(outdir):
            done = [f for f in os.listdir(outdir) if f.endswith(".tga")]
            if len(done) >= count:
                return done
        assert proc.poll() is None, "fc-master ended early:\n" + proc.communicate()[1]
        time.sleep(0.02)
    raise AssertionError("no %d frames after %d s" % (count, timeout))


def program_pids(coordinator, name):
    """Marked processes running the program `name` (by argv[0])."""
    return [p for p in coordinator.pids()
            if os.path.basename(coordinator_cmdline(p).split(" ")[0]) == name]


def slave_pids(coordinator):
    return program_pids(coordinator, "fc-slave")


# --- correctness of every division scheme ---------------------------------------------------

@pytest.mark.parametrize("fc", [False, True], ids=["no-fc", "fc"])
@pytest.mark.parametrize("slaves", [1, 2, 3])
@pytest.mark.parametrize("division", ["sequence", "frame", "hybrid"])
def test_division_matches_single_process(coordinator, coordinator_references, tmp_path,
                                         division, slaves, fc):
    out = tmp_path / "out"
    stats = tmp_path / "stats.json"
    r = coordinator.run((["--no-fc"] if not fc else []) +
                        ["--quiet", "--division", division, "--slaves", str(slaves),
                         "--stats", str(stats), SCENE] + SMALL + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    if fc:
        # The renderer has the fc options, so the master used them.
        assert "frame coherence" not in r.stderr.lower(), r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, SMALL))
    # Invariant: the master stops its pvmd and every slave and renderer.
    assert coordinator.wait_no_processes() == []

    s = coordinator_stats(stats)
    assert s["success"] and s["division"] == division
    assert s["virtual_machine"] == "private"
    assert s["frames_total"] == 8 and s["frames_rendered"] == 8
    assert [h["slaves"] for h in s["hosts"]] == [slaves]
    ntiles = 1 if division == "sequence" else 6     # 160x120 in tiles of 64 (the default)
    for f in s["frames"]:
        # Invariant: each frame is assembled from each tile exactly once, with its statistics.
        assert sorted(t["tile"] for t in f["tiles"]) == list(range(ntiles))
        assert f["rays"] > 0 and f["host"] and f["time"] >= 0
        # Invariant: one parse per slave and frame at most, however many tiles it holds.
        assert 1 <= f["parses"] <= slaves, f
    for j in s["jobs"]:
        assert j["status"] in ("done", "cancelled", "duplicate", "stopped"), j
        assert j["host"] and j["tiles"] and j["parse"] >= 0


# Antialiasing method 1 traces a border around each 32-pixel render block, so a pixel depends
# on where block edges fall; jitter, method 2 and dithering have their own state. Tiles are
# rendered on the whole area's block grid and dithering runs on the assembled frame, so every
# combination equals one process. Slave counts cycle through 1-3 to keep the module fast.
AA_SETTINGS = {
    "no-aa": ["-A"],
    "am1": ["+A0.1", "+AM1"],
    "am1-jitter": ["+A0.1", "+AM1", "+J0.8"],
    "am2": ["+A0.1", "+AM2", "+R2"],
    "am2-jitter": ["+A0.05", "+AM2", "+R2", "+J"],
}


@pytest.mark.parametrize("tile", [80, 37])
@pytest.mark.parametrize("aa", sorted(AA_SETTINGS))
@pytest.mark.parametrize("division", ["frame", "hybrid"])
def test_tiles_exact_under_every_antialiasing(coordinator, coordinator_references, tmp_path,
                                              division, aa, tile):
    opts = ["+FT", "+W160", "+H120", "+KFI1", "+KFF3"] + AA_SETTINGS[aa]
    slaves = 1 + (sorted(AA_SETTINGS).index(aa) + tile) % 3
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", "--division", division, "--tile", str(tile),
                         "--slaves", str(slaves), SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, opts))


@pytest.mark.parametrize("method", ["fs", "d1", "d2", "b4"])
@pytest.mark.parametrize("division", ["frame", "sequence"])
def test_dithering_exact(coordinator, coordinator_references, tmp_path, division, method):
    # Error diffusion (d1, d2, fs) runs over the whole image; Bayer (b4) is per pixel.
    opts = ["+FT", "+W160", "+H120", "+KFI1", "+KFF2", "+A0.1", "+AM1", "Dither=on",
            "Dither_Method=" + method]
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--division", division, "--tile", "37", "--slaves", "3",
                         SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, opts))


@pytest.mark.parametrize("aa", ["no-aa", "am2"])
def test_tile_edges_share_no_render_block(coordinator, coordinator_references, tmp_path, aa):
    # 80-pixel tiles cut 32-pixel render blocks; where no pixel depends on the block grid
    # (every setting but AA method 1) the slaves render blocks that fit in the tiles, so the
    # tiles together trace what one whole-frame job traces: no block twice.
    opts = ["+FT", "+W160", "+H120", "+KFI1", "+KFF3"] + AA_SETTINGS[aa]

    def rays(division, out):
        stats = tmp_path / (division + ".json")
        r = coordinator.run(["--no-fc", "--quiet", "--no-duplicates", "--division", division,
                             "--tile", "80", "--slaves", "2", "--stats", str(stats), SCENE] +
                            opts + ["-o", str(out)])
        assert r.returncode == 0, r.stderr
        return sum(h["rays"] for h in coordinator_stats(stats)["hosts"])

    tiled = rays("frame", tmp_path / "frame")
    whole = rays("sequence", tmp_path / "sequence")
    assert_same_frames(tmp_path / "frame", coordinator_references.frames(SCENE, opts))
    if aa == "no-aa":
        assert tiled == whole
    else:
        # Method 2 shares the corner samples of neighbouring pixels within a block, so other
        # block sizes trace a few corners more or fewer, far from whole blocks twice.
        assert abs(tiled - whole) <= 0.02 * whole, (tiled, whole)


@pytest.mark.parametrize("aa", ["am1", "no-aa"])
def test_frame_coherence_tiles_exact(coordinator, coordinator_references, tmp_path, aa):
    # fc keeps each slave's tiles coherent from frame to frame, under AA method 1 too; without
    # AA the slaves render blocks of 48 pixels, the tiles' own.
    opts = ["+FT", "+W160", "+H120", "+KFI1", "+KFF8"] + AA_SETTINGS[aa]
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--division", "frame", "--tile", "48", "--slaves", "2",
                         SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, opts))


def test_ini_file_renders_unchanged(coordinator, coordinator_references, tmp_path):
    # moving.ini names its scene relative to the working directory, as POV-Ray expects.
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", "--slaves", "2", "moving.ini", "+FT", "-o", str(out)])
    assert r.returncode == 0, r.stderr
    ref = coordinator_references.frames("moving.ini", [])
    assert sorted(ref) == ["moving%02d.tga" % i for i in range(1, 13)]
    assert_same_frames(out, ref)


@pytest.mark.parametrize("opts", [
    ["+FT", "+W96", "+H72", "+KFI1", "+KFF12", "+SF7", "+EF10"],           # subset: moving07..10
    ["+FT", "+W96", "+H72", "+KFI1", "+KFF9", "+KC"],                       # cyclic: digits of 10
    ["+FT", "+W96", "+H72", "+KFI3", "+KFF11", "Frame_Step=3"],             # frames 3, 6, 9
    ["+FT", "+W96", "+H72", "+KFI98", "+KFF101"],                           # names widen to 3 digits
    ["+FT", "+W96", "+H72", "+KFI1", "+KFF12", "Subset_End_Frame=0.5"],     # half: moving01..06
], ids=["subset", "cyclic", "step", "digits", "fraction"])
def test_frame_ranges_and_names_follow_povray(coordinator, coordinator_references, tmp_path,
                                             opts):
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", "--division", "sequence", "--slaves", "2",
                         SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, opts))


def test_still_image_and_render_area(coordinator, coordinator_references, tmp_path):
    # No animation options: one image; a partial render area keeps zeros outside, like POV-Ray.
    opts = ["+FT", "+W160", "+H120", "+SC20", "+EC130", "+SR10", "+ER100"]
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--quiet", "--division", "frame", "--tile", "40",
                         "--slaves", "3", SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    ref = coordinator_references.frames(SCENE, opts)
    assert sorted(ref) == ["moving.tga"]
    assert_same_frames(out, ref)


def test_joins_running_virtual_machine(coordinator, coordinator_references, tmp_path):
    env = coordinator.env({"PVM_ALLOW_ROOT": "1"})
    pvmd = coordinator.start_running_vm()
    try:
        out = tmp_path / "out"
        stats = tmp_path / "stats.json"
        r = coordinator.run(["--no-fc", "--quiet", "--stats", str(stats), SCENE] + SMALL +
                            ["-o", str(out)], env={"PVM_ALLOW_ROOT": "1"})
        assert r.returncode == 0, r.stderr
        assert coordinator_stats(stats)["virtual_machine"] == "running", r.stderr
        assert_same_frames(out, coordinator_references.frames(SCENE, SMALL))
        # Invariant: a virtual machine the master did not start keeps running, without slaves.
        deadline = time.time() + 10
        while slave_pids(coordinator) and time.time() < deadline:
            time.sleep(0.1)
        assert slave_pids(coordinator) == [], r.stderr
        assert pvmd in coordinator.pids(), r.stderr
    finally:
        subprocess.run(["pvm"], input="halt\n", env=env, capture_output=True, text=True,
                       timeout=30)
    assert coordinator.wait_no_processes() == []


@pytest.mark.parametrize("fc", [False, True], ids=["no-fc", "fc"])
def test_default_slaves_per_host(coordinator, coordinator_references, tmp_path, fc):
    out = tmp_path / "out"
    stats = tmp_path / "stats.json"
    log = tmp_path / "renderers.log"
    script = tmp_path / "logging-povray"
    script.write_text(f"""#!/bin/sh
case "$*" in *Frame_Control=*) echo "$*" >> {log} ;; esac
exec {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    r = coordinator.run((["--no-fc"] if not fc else []) +
                        ["--quiet", "--povray", str(script), "--division", "frame",
                         "--stats", str(stats), SCENE] + SMALL + ["-o", str(out)], renderer=False)
    assert r.returncode == 0, r.stderr
    cores = os.cpu_count()
    renderers = log.read_text().splitlines()
    # Invariant: with fc one slave per host, its renderer on every core (one first frame
    # and one parse per frame for the host); without fc one single-threaded slave per core.
    want = (1, cores) if fc else (cores, 1)
    assert [h["slaves"] for h in coordinator_stats(stats)["hosts"]] == [want[0]]
    assert len(renderers) == want[0], renderers
    for line in renderers:
        # fc-slave puts +WT<threads> first; a later +WT would override it
        threads = [w for w in line.split() if w.startswith("+WT")]
        assert threads == [f"+WT{want[1]}"], line
    assert_same_frames(out, coordinator_references.frames(SCENE, SMALL))


# --- faults ----------------------------------------------------------------------------------

@pytest.mark.parametrize("division", ["sequence", "frame"])
def test_resume_after_killing_master(coordinator, coordinator_references, tmp_path, division):
    out = tmp_path / "out"
    args = ["--no-fc", "--quiet", "--division", division, "--slaves", "2", SCENE] + SLOW + \
           ["-o", str(out)]
    ref = coordinator_references.frames(SCENE, SLOW)
    p = coordinator.start(args)
    wait_for_frames(out, 3, p)
    p.send_signal(signal.SIGKILL)
    p.communicate()
    # Invariant: a killed master takes its private pvmd, slaves and renderers with it.
    assert coordinator.wait_no_processes() == []
    # Killed while writing a frame, the master leaves it under its temporary name, never a
    # final one (the resume below removes it).
    temporary = [f for f in frame_files(out) if f.endswith(".fc-tmp")]
    before = [f for f in frame_files(out) if f not in temporary]
    assert len(temporary) <= 1 and all(t[:-len(".fc-tmp")] in ref for t in temporary), temporary
    assert 3 <= len(before) < len(ref)
    # Invariant: only complete frames exist, and under final names only.
    assert_same_frames(out, ref, only=before, temporary=temporary)

    stats = tmp_path / "stats.json"
    r = coordinator.run(args + ["--stats", str(stats)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, ref)
    s = coordinator_stats(stats)
    # Invariant: the second run renders only the frames that were missing.
    assert s["frames_resumed"] == len(before)
    assert s["frames_rendered"] == len(ref) - len(before)
    assert coordinator.wait_no_processes() == []


def test_frames_complete_in_order_while_rendering(coordinator, coordinator_references,
                                                  tmp_path):
    # Frame division: the slaves divide each frame, so frames are written one after the other
    # from the start, and the master holds a few frames, however many the animation has.
    out = tmp_path / "out"
    stats = tmp_path / "stats.json"
    # 48 frames: the first frame's time is mostly the renderers' start, and the whole run
    # must be long beside it for "from the start" to show.
    opts = ["+FT", "+W160", "+H120", "+KFI1", "+KFF48", "+A0.1", "+AM2", "+R3"]
    r = coordinator.run(["--no-fc", "--quiet", "--division", "frame", "--tile", "40",
                         "--slaves", "2", "--stats", str(stats), SCENE] + opts +
                        ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, opts))
    s = coordinator_stats(stats)
    assert s["max_frames_held"] <= 6, s["max_frames_held"]
    finished = [f["finished_at"] for f in s["frames"]]
    assert finished[0] < s["elapsed"] / 3, finished
    # Nearly in order: no frame is finished after the frames beyond the scheduler's window
    # (Schedule::kWindow, 4, plus two whole frames queued per slave: a slave slowed by a busy
    # core may hold a frame while the other renders the next eight).
    lag = 4 + 2 * 2 + 1
    for k in range(len(finished) - lag):
        assert finished[k] <= finished[k + lag], finished


def test_private_pvmd_and_its_tasks_get_at_most_fd_setsize_descriptors(coordinator,
                                                                         coordinator_references,
                                                                         tmp_path):
    """The pvmd closes every descriptor up to the soft limit in each task it spawns (about
    0.2 s a slave under the 1,048,576 many containers set), and PVM's select() cannot use one
    past FD_SETSIZE: fc-master's private pvmd, so its slaves and their renderers, get 1024."""
    hard = resource.getrlimit(resource.RLIMIT_NOFILE)[1]
    high = 8192 if hard == resource.RLIM_INFINITY else min(8192, hard)
    if high <= 1024:
        pytest.skip(f"the hard limit on open files ({hard}) leaves nothing above 1024 to lower")
    out = tmp_path / "out"
    log = tmp_path / "limits.log"
    script = tmp_path / "limit-logging-povray"
    script.write_text(f"""#!/bin/sh
case "$*" in *Frame_Control=*) ulimit -Sn >> {log} ;; esac
exec {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    r = coordinator.run(["--no-fc", "--quiet", "--povray", str(script), "--division", "frame",
                         "--slaves", "2", SCENE] + SMALL + ["-o", str(out)], renderer=False,
                        prefix=("sh", "-c", f'ulimit -Sn {high} && exec "$@"', "sh"))
    assert r.returncode == 0, r.stderr
    limits = log.read_text().split()
    # Invariant: every renderer a slave started (so the slave and the pvmd) had the lowered
    # limit, not the master's.
    assert len(limits) >= 2 and all(int(n) == 1024 for n in limits), limits
    assert_same_frames(out, coordinator_references.frames(SCENE, SMALL))


def test_renderer_console_does_not_wake_the_slave(coordinator, coordinator_references,
                                                  tmp_path):
    """POV-Ray writes its status lines to the console in about nine writes a frame, and the
    console only explains failures: after the renderer's first frame the slave stops polling
    it (it reads it when the frame record or the next job wakes it), so the console's
    writes no longer wake the slave."""
    frames = 24
    opts = ["+FT", "+W160", "+H120", "+KFI1", "+KFF%d" % frames]
    out = tmp_path / "out"
    polls = tmp_path / "slave-polls"
    wrapper = tmp_path / "traced-slave"
    wrapper.write_text(f'#!/bin/sh\nexec strace -qq -o {polls} -e trace=poll {FC_SLAVE} "$@"\n')
    wrapper.chmod(0o755)
    r = coordinator.run(["--quiet", "--slave", str(wrapper), "--division", "frame", "--slaves",
                         "1", SCENE] + opts + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, opts))
    # Each poll: the descriptors it waited on, and those that woke it. How many wake-ups a
    # frame takes depends on the machine's load (a frame record read in two pieces wakes
    # the slave twice), so the test follows the console's descriptor itself.
    calls = []
    for line in polls.read_text().splitlines():
        if line.startswith("poll(["):
            waited, _, result = line.partition("]")
            calls.append((set(re.findall(r"fd=(\d+), events", waited)),
                          set(re.findall(r"fd=(\d+), revents", result))))
    assert calls, "the slave never polled"
    # The console: the renderer's descriptor the slave polls at first and then no more
    # (the pvmd's and the frame channel's stay while the renderer runs).
    steady = calls[len(calls) // 2][0]
    console = set().union(*(waited for waited, _ in calls)) - steady
    assert len(console) == 1, (console, steady)
    polled = [i for i, (waited, _) in enumerate(calls) if console <= waited]
    # Invariant: the console is polled during the renderer's first frame only, in one
    # stretch, and wakes the slave fewer times than there are frames (the slave that polled
    # it throughout woke 4-5 times a frame, about twice for the console).
    assert polled == list(range(polled[0], polled[0] + len(polled))), polled
    woken_by_console = sum(1 for _, ready in calls if console & ready)
    assert woken_by_console < frames, woken_by_console
    assert len(polled) < len(calls) / 2, (len(polled), len(calls))


def test_chatty_scene_fills_the_console_and_still_renders(coordinator, coordinator_references,
                                                          tmp_path):
    """A scene that, from its third frame on, writes more to the console in a frame (#debug,
    75 KB) than its pipe holds: the slave, which stopped polling the quiet console after the
    first frame, reads it when its poll times out and polls it from then on; the renderer is
    never left blocked on a full pipe."""
    scene = tmp_path / "chatty.pov"
    line = "x" * 49
    with open(os.path.join(COORDINATOR_SCENES, SCENE)) as f:
        scene.write_text(f.read() + '#if (frame_number >= 3) #for (I, 1, 1500) #debug "%s\\n" '
                         '#end #end\n' % line)
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--division", "frame", "--slaves", "2", str(scene)] + SMALL +
                        ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert_same_frames(out, coordinator_references.frames(str(scene), SMALL))
    assert coordinator.wait_no_processes() == []


def renderer_wrapper(tmp_path, failures):
    """A renderer that fails (exit status 3, as a broken host would) the first `failures`
    renders fc-slave starts, then runs povray-fc; failures < 0: always."""
    counter = tmp_path / "failures"
    script = tmp_path / "flaky-povray"
    real = coordinator_renderer()
    script.write_text(f"""#!/bin/sh
case "$*" in *Frame_Control=*)
  n=$(flock {counter}.lock sh -c 'n=$(cat {counter} 2>/dev/null || echo 0); n=$((n + 1)); echo $n > {counter}; echo $n')
  if [ {failures} -lt 0 ] || [ "$n" -le {failures} ]; then echo "simulated host failure" >&2; exit 3; fi
esac
exec {real} "$@"
""")
    script.chmod(0o755)
    return script


def test_slave_failure_is_retried(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    wrapper = renderer_wrapper(tmp_path, 2)
    r = coordinator.run(["--no-fc", "--povray", str(wrapper), "--division", "frame",
                         "--slaves", "2", SCENE] + SMALL + ["-o", str(out)], renderer=False)
    assert r.returncode == 0, r.stderr
    # Invariant: a host's failure is not the scene's: the work is done again, with a warning.
    assert r.stderr.count("trying again") == 2, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, SMALL))
    assert coordinator.wait_no_processes() == []


def test_failing_host_is_left_out(coordinator, tmp_path):
    out = tmp_path / "out"
    wrapper = renderer_wrapper(tmp_path, -1)
    r = coordinator.run(["--no-fc", "--povray", str(wrapper), "--division", "frame",
                         "--slaves", "2", SCENE] + SMALL + ["-o", str(out)], renderer=False)
    # Three failures leave the only host out; nothing is left to render with.
    assert r.returncode == 1
    assert "left out" in r.stderr and "simulated host failure" in r.stderr, r.stderr
    assert frame_files(out) == []
    assert coordinator.wait_no_processes() == []


def killing_renderer(tmp_path, kills):
    """A renderer killed by SIGKILL (as the kernel's out-of-memory killer kills) 0.3 s into
    each of the first `kills` renders fc-slave starts (kills < 0: every one), in the middle of
    its work; POV-Ray has printed its progress lines by then."""
    counter = tmp_path / "kills"
    script = tmp_path / "killed-povray"
    script.write_text(f"""#!/bin/sh
case "$*" in *Frame_Control=*)
  n=$(flock {counter}.lock sh -c 'n=$(cat {counter} 2>/dev/null || echo 0); n=$((n + 1)); echo $n > {counter}; echo $n')
  if [ {kills} -lt 0 ] || [ "$n" -le {kills} ]; then (sleep 0.3; kill -9 $$) & fi
esac
exec {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    return script


def test_killed_renderer_is_retried(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    script = killing_renderer(tmp_path, 1)
    r = coordinator.run(["--no-fc", "--povray", str(script), "--division", "sequence",
                         "--slaves", "2", SCENE] + SLOW + ["-o", str(out)], renderer=False)
    # Invariant: a killed renderer is the host's problem: its work is done again elsewhere.
    assert r.returncode == 0, r.stderr
    assert "killed by signal 9" in r.stderr and "trying again" in r.stderr, r.stderr
    # The warning says what SIGKILL usually means, not only that the renderer "stopped".
    assert "out of memory" in r.stderr, r.stderr
    # Invariant: only POV-Ray's error lines are shown, never its progress lines.
    assert "Rendered" not in r.stderr, r.stderr
    assert_same_frames(out, coordinator_references.frames(SCENE, SLOW))
    assert coordinator.wait_no_processes() == []


def test_renderer_killed_every_time_fails_briefly(coordinator, tmp_path):
    out = tmp_path / "out"
    script = killing_renderer(tmp_path, -1)
    r = coordinator.run(["--no-fc", "--povray", str(script), "--division", "sequence",
                         "--slaves", "2", SCENE] + SLOW + ["-o", str(out)], renderer=False)
    # The retry and blocklist rules end it: a tile that failed 3 times, or no host left.
    assert r.returncode == 1
    assert "killed by signal 9" in r.stderr and "Rendered" not in r.stderr, r.stderr
    assert len(r.stderr.splitlines()) < 25, r.stderr
    assert coordinator.wait_no_processes() == []


SHELLOUT_INI = """\
Pre_Scene_Command=sh -c "echo pre-scene %n >> {log}"
Pre_Frame_Command=sh -c "echo pre-frame %n %k >> {log}"
Post_Frame_Command=sh -c "echo post-frame %n >> {log}"
Post_Scene_Command=sh -c "echo post-scene %n >> {log}"
"""


def allow_shellouts(tmp_path):
    """A command prefix that runs its command in a private mount namespace where povray.conf
    allows shell-outs (Debian's forbids them; the machine's own file stays untouched)."""
    conf = tmp_path / "povray.conf"
    text = open("/etc/povray/3.7/povray.conf").read()
    conf.write_text(text.replace("\nforbidden", "\nallowed"))
    return ["unshare", "-m", "--", "sh", "-c",
            'mount --bind "$0" /etc/povray/3.7/povray.conf && exec "$@"', str(conf)]


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root for a private mount namespace")
def test_shellouts_run_once_as_in_one_process(coordinator, tmp_path):
    prefix = allow_shellouts(tmp_path)
    opts = ["+FT", "+W64", "+H48", "+KFI1", "+KFF4"]
    single_log, master_log = tmp_path / "single.log", tmp_path / "master.log"
    (tmp_path / "single.ini").write_text(SHELLOUT_INI.format(log=single_log))
    (tmp_path / "master.ini").write_text(SHELLOUT_INI.format(log=master_log))
    single = subprocess.run(prefix + [coordinator_renderer(), SCENE, str(tmp_path / "single.ini"),
                                      "-D", "-V", "+O%s/s" % tmp_path] + opts,
                            cwd=COORDINATOR_SCENES, capture_output=True, text=True, timeout=60)
    assert single.returncode == 0, single.stderr
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--division", "frame", "--tile", "16", "--slaves", "3",
                         SCENE, str(tmp_path / "master.ini")] + opts + ["-o", str(out)],
                        prefix=prefix)
    assert r.returncode == 0, r.stderr
    want = single_log.read_text().splitlines()
    got = master_log.read_text().splitlines()
    # Invariant: each command runs as often as in one process (scene once, frame once per
    # frame, never per tile or slave), with the same frame number and clock.
    assert sorted(got) == sorted(want), (got, want)
    assert got[0] == "pre-scene 1" and got[-1] == "post-scene 4"
    for n in range(1, 5):
        assert got.index("post-frame %d" % n) > got.index("pre-frame %d %s" % (
            n, next(w.split()[2] for w in want if w.startswith("pre-frame %d " % n))))
    assert len(frame_files(out)) == 4
    assert coordinator.wait_no_processes() == []


def test_forbidden_shellout_keeps_its_return_action(coordinator, tmp_path):
    # Debian's povray.conf forbids shell-outs; POV-Ray then counts the command as failed,
    # and Pre_Scene_Return=q makes it quit before rendering (exit status 0).
    ini = tmp_path / "quit.ini"
    ini.write_text("Pre_Scene_Command=touch %s\nPre_Scene_Return=q\n" % (tmp_path / "ran"))
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", SCENE, str(ini)] + SMALL + ["-o", str(out)])
    assert r.returncode == 0, r.stderr
    assert "quit rendering" in r.stderr and "prohibited" in r.stderr
    assert not (tmp_path / "ran").exists()
    assert not out.exists() or frame_files(out) == []
    assert coordinator.wait_no_processes() == []


def test_nothing_to_do_when_complete(coordinator, tmp_path):
    out = tmp_path / "out"
    args = ["--no-fc", "--quiet", SCENE, "+FT", "+W64", "+H48", "+KFI1", "+KFF3", "-o", str(out)]
    assert coordinator.run(args).returncode == 0
    mtimes = {f: os.stat(out / f).st_mtime_ns for f in frame_files(out)}
    r = coordinator.run(args)
    assert r.returncode == 0 and "nothing to render" in r.stderr
    assert {f: os.stat(out / f).st_mtime_ns for f in frame_files(out)} == mtimes


def test_killed_slave_work_is_requeued(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    p = coordinator.start(["--no-fc", "--division", "sequence", "--slaves", "2", SCENE] +
                          SLOW + ["-o", str(out)])
    wait_for_frames(out, 2, p)
    victims = slave_pids(coordinator)
    assert len(victims) == 2
    os.kill(victims[0], signal.SIGKILL)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    assert "exited" in err
    assert_same_frames(out, coordinator_references.frames(SCENE, SLOW))
    assert coordinator.wait_no_processes() == []


def test_unresponsive_slave_times_out(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    p = coordinator.start(["--no-fc", "--timeout", "2", "--division", "sequence", "--slaves",
                           "2", SCENE] + SLOW + ["-o", str(out)])
    wait_for_frames(out, 2, p)
    victim = slave_pids(coordinator)[0]
    os.kill(victim, signal.SIGSTOP)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    assert "silent" in err
    assert_same_frames(out, coordinator_references.frames(SCENE, SLOW))
    assert coordinator.wait_no_processes() == []


def test_interrupt_stops_everything(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    p = coordinator.start(["--no-fc", "--division", "frame", "--slaves", "2", SCENE] + SLOW +
                          ["-o", str(out)])
    wait_for_frames(out, 1, p)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "interrupted" in err
    assert coordinator.wait_no_processes() == []
    assert_same_frames(out, coordinator_references.frames(SCENE, SLOW),
                       only=frame_files(out))


# --- bad input -------------------------------------------------------------------------------

def test_scene_that_does_not_parse(coordinator, tmp_path):
    out = tmp_path / "out"
    r = coordinator.run(["--no-fc", "--slaves", "3", "broken.pov", "+FT", "+W64", "+H48", "+KFI1",
                         "+KFF6", "-o", str(out)])
    assert r.returncode == 1
    # Invariant: the renderer's error (file, line, message) is reported once.
    assert r.stderr.count("Parse Error") == 1, r.stderr
    assert "broken.pov' line 9" in r.stderr
    assert "No matching } in 'sphere'" in r.stderr
    assert frame_files(out) == []
    assert coordinator.wait_no_processes() == []


def test_scene_failing_late_keeps_only_complete_frames(coordinator, coordinator_references,
                                                       tmp_path):
    out = tmp_path / "out"
    opts = ["+FT", "+W64", "+H48", "+KFI1", "+KFF8"]
    r = coordinator.run(["--no-fc", "--division", "sequence", "--slaves", "2", "fails-late.pov"]
                        + opts + ["-o", str(out)])
    assert r.returncode == 1
    assert r.stderr.count("deliberate failure") == 1, r.stderr
    # Frames 1-4 have clock < 0.5 and render; whatever was finished is complete and exact.
    ref = coordinator_references.frames("fails-late.pov", ["+FT", "+W64", "+H48", "+KFI1", "+KFF8",
                                                           "+SF1", "+EF4"])
    done = frame_files(out)
    assert set(done) <= set(ref)
    assert_same_frames(out, ref, only=done)
    assert coordinator.wait_no_processes() == []


def test_missing_scene_file(coordinator, tmp_path):
    r = coordinator.run(["--no-fc", "no-such-scene.pov", "-o", str(tmp_path / "out")])
    assert r.returncode == 1
    assert "no-such-scene.pov" in r.stderr and "Cannot open input file" in r.stderr
    assert coordinator.wait_no_processes() == []


@pytest.mark.parametrize("args", [
    ["--frobnicate", SCENE, "-o", "OUT"],
    ["--division", "diagonal", SCENE, "-o", "OUT"],
    ["--tile", "abc", SCENE, "-o", "OUT"],
    ["--slaves", "0", SCENE, "-o", "OUT"],
    ["--no-fc=yes", SCENE, "-o", "OUT"],
    [SCENE, "-o", "OUT", "--stats"],
    [SCENE, "-o"],
    ["-o", "OUT"],
], ids=["unknown", "division", "tile", "slaves", "flag-value", "missing-value", "missing-dir",
        "no-scene"])
def test_bad_options(coordinator, tmp_path, args):
    args = [str(tmp_path / "out") if a == "OUT" else a for a in args]
    r = coordinator.run(args, renderer=False)
    assert r.returncode == 2
    assert "usage: fc-master" in r.stderr
    assert not (tmp_path / "out").exists()
    assert coordinator.pids() == []


@pytest.mark.parametrize("which", ["slave", "povray"])
def test_missing_program(coordinator, tmp_path, which):
    r = coordinator.run(["--no-fc", "--" + which, "/nonexistent/fc-program", SCENE] + SMALL +
                        ["-o", str(tmp_path / "out")])
    assert r.returncode == 1
    assert "/nonexistent/fc-program" in r.stderr
    assert not (tmp_path / "out").exists() or frame_files(tmp_path / "out") == []
    assert coordinator.wait_no_processes() == []


def test_missing_hostfile_is_a_usage_error(coordinator, tmp_path):
    missing = tmp_path / "no-such-hosts"
    r = coordinator.run(["--no-fc", "--hostfile", str(missing), SCENE] + SMALL +
                        ["-o", str(tmp_path / "out")])
    # Invariant: a host file that cannot be read stops the run, named, before anything runs.
    assert r.returncode == 2
    assert str(missing) in r.stderr and "No such file or directory" in r.stderr, r.stderr
    assert "usage: fc-master" in r.stderr
    assert not (tmp_path / "out").exists()
    assert coordinator.pids() == []


def files_only_name_lookups(tmp_path):
    """A command prefix: run in a private mount namespace where host names resolve from
    /etc/hosts only (no test may ask DNS)."""
    conf = tmp_path / "nsswitch.conf"
    lines = open("/etc/nsswitch.conf").read().splitlines()
    conf.write_text("".join(("hosts: files" if l.startswith("hosts:") else l) + "\n"
                            for l in lines))
    return ["unshare", "-m", "--", "sh", "-c",
            'mount --bind "$0" /etc/nsswitch.conf && exec "$@"', str(conf)]


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root for a private mount namespace")
@pytest.mark.parametrize("private", [True, False], ids=["private", "running"])
def test_host_that_cannot_be_added_is_an_error(coordinator, tmp_path, private):
    hosts = tmp_path / "hosts"
    hosts.write_text("# a cluster\nfc-no-such-host-1.invalid\n")
    out = tmp_path / "out"
    prefix = files_only_name_lookups(tmp_path)
    env = {"PVM_ALLOW_ROOT": "1"}
    if not private:
        started = subprocess.run(prefix + ["pvm"], input="quit\n", env=coordinator.env(env),
                                 capture_output=True, text=True, timeout=30)
        assert "pvmd still running" in started.stdout + started.stderr, started
    try:
        r = coordinator.run(["--no-fc", "--hostfile", str(hosts), SCENE] + SMALL +
                            ["-o", str(out)], prefix=prefix, env=env)
    finally:
        if not private:
            subprocess.run(prefix + ["pvm"], input="halt\n", env=coordinator.env(env),
                           capture_output=True, text=True, timeout=30)
    # Invariant: the host is named with the reason, and nothing renders without it.
    assert r.returncode == 1, r.stderr
    assert "fc-no-such-host-1.invalid" in r.stderr and "does not resolve" in r.stderr, r.stderr
    assert not out.exists() or frame_files(out) == []
    assert coordinator.wait_no_processes() == []


def test_stale_pvmd_file_is_removed(coordinator, coordinator_references, tmp_path):
    # A pvmd killed by SIGKILL leaves its pvmd.<uid> file behind in PVM_TMP.
    coordinator.start_running_vm()
    stale = coordinator.pvm_tmp / ("pvmd.%d" % os.getuid())
    assert stale.exists()
    for pid in program_pids(coordinator, "pvmd"):
        os.kill(pid, signal.SIGKILL)
    assert coordinator.wait_no_processes() == []
    assert stale.exists()
    out = tmp_path / "out"
    start = time.time()
    r = coordinator.run(["--no-fc", "--quiet", SCENE] + SMALL + ["-o", str(out)],
                        env={"PVM_ALLOW_ROOT": "1"})
    # Invariant: no pvmd owns the file: it is removed, saying so, and the render goes on at
    # once (libpvm would retry for 13 s and fail).
    assert r.returncode == 0, r.stderr
    assert "removed %s" % stale in r.stderr, r.stderr
    assert not stale.exists()
    assert time.time() - start < 10
    assert_same_frames(out, coordinator_references.frames(SCENE, SMALL))
    assert coordinator.wait_no_processes() == []


def test_help(coordinator):
    r = coordinator.run(["--help"], renderer=False)
    assert r.returncode == 0
    assert r.stdout.startswith("usage: fc-master") and "--division" in r.stdout


# --- progress and statistics -----------------------------------------------------------------

def test_progress_lines_and_summary(coordinator, tmp_path):
    # A line every 0.1 s: the render takes about half a second.
    r = coordinator.run(["--no-fc", "--progress", "0.1", "--slaves", "2", SCENE, "+FT", "+W160",
                         "+H120", "+KFI1", "+KFF8", "+A0.1", "+AM2", "+R3", "-o",
                         str(tmp_path / "out")])
    assert r.returncode == 0, r.stderr
    lines = r.stderr.splitlines()
    # Not a terminal: plain periodic lines, no carriage returns.
    assert "\r" not in r.stderr
    assert any(l.startswith("fc-master: ") and " frames (" in l for l in lines), r.stderr
    assert any("8 frame(s) rendered" in l for l in lines)
    header = [l for l in lines if l.split()[:1] == ["host"]]
    assert header and "rays" in header[0] and "busy" in header[0]


def test_slave_renderers_run_as_batch_tasks(coordinator, tmp_path):
    # A slave's renderer runs under SCHED_BATCH (coordinator/slave/renderer.cpp says why); the
    # master's probes, which a user waits for, keep the usual policy. A renderer that records
    # its policy and its role, then runs the real one.
    log = tmp_path / "policies.txt"
    script = tmp_path / "policy-povray"
    script.write_text(f"""#!/bin/sh
role=probe
for a; do case $a in Frame_Control=*) role=renderer;; esac; done
echo "$role $(chrt -p $$ | sed -n 's/.*scheduling policy: //p')" >> {log}
exec {coordinator_renderer()} "$@"
""")
    script.chmod(0o755)
    out = tmp_path / "out"
    r = coordinator.run(["--quiet", "--povray", str(script), "--division", "frame", "--slaves",
                         "2", SCENE] + SMALL + ["-o", str(out)], renderer=False)
    assert r.returncode == 0, r.stderr
    assert len(frame_files(out)) == 8, frame_files(out)
    seen = [line.split() for line in log.read_text().splitlines()]
    renderers = [policy for role, policy in seen if role == "renderer"]
    probes = [policy for role, policy in seen if role == "probe"]
    assert renderers and set(renderers) == {"SCHED_BATCH"}, seen
    assert probes and "SCHED_BATCH" not in probes, seen
