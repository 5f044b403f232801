"""fc-master judges its slaves by real progress, never hangs, and with --keep-going renders
every frame it can.

A stopped slave or renderer, or a frame that never ends, is noticed by its deadline (learned
from the run, at least 8 s) and its work copied to another slave; a frame that hangs or fails
on two hosts is reported with its number and POV-Ray's last words. Each test gives fc-master a
--timeout far beyond the test's own bound, so that only the progress rules can end the run in
time. (How fast, measured: scripts/liveness-goals.)
"""
import os
import shutil
import signal
import time

import pytest

from conftest import COORDINATOR_SCENES, coordinator_cmdline, frame_files, load_rgb
from test_coordinator import SCENE, SLOW, assert_same_frames, slave_pids, wait_for_frames

pytestmark = pytest.mark.usefixtures("coordinator_build")

# No slave is declared lost by silence within a test: the copies must do it.
PATIENT = ["--timeout", "600"]


def renderer_pids(coordinator):
    """The marked renderer processes (povray-fc started by fc-slave)."""
    return [p for p in coordinator.pids()
            if "Frame_Control=" in coordinator_cmdline(p)]


def parent_pid(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            return int(f.read().rsplit(")", 1)[1].split()[1])
    except (OSError, ValueError, IndexError):
        return 0


def frame_scene(tmp_path, name, trouble):
    """moving.pov with `trouble` (SDL) for frame 5 only, in tmp_path; returns its path."""
    scene = tmp_path / name
    text = open(os.path.join(COORDINATOR_SCENES, SCENE)).read()
    scene.write_text(text + "\n#if (frame_number = 5)\n%s\n#end\n" % trouble)
    return scene


def assert_same_as(outdir, stem, reference, skip):
    """outdir holds the reference's frames (of moving.pov) but frame `skip`, named for stem,
    pixel for pixel."""
    expected = sorted(f.replace("moving", stem) for f in reference
                      if skip is None or not f.endswith("%d.tga" % skip))
    assert frame_files(outdir) == expected
    for name in expected:
        got = load_rgb(os.path.join(outdir, name))
        assert (got == reference[name.replace(stem, "moving")]).all(), name


@pytest.mark.parametrize("division", ["frame", "sequence"])
def test_stopped_slave_work_is_copied_and_no_healthy_slave_is_lost(
        coordinator, coordinator_references, tmp_path, division):
    out = tmp_path / "out"
    p = coordinator.start(PATIENT + ["--no-fc", "--division", division, "--slaves", "2", SCENE] +
                          SLOW + ["-o", str(out)])
    wait_for_frames(out, 2, p)
    victim = slave_pids(coordinator)[0]
    os.kill(victim, signal.SIGSTOP)
    # Once the stall is noticed, the healthy slave renders with the host's every core (the
    # stopped one's too): its renderer restarts with them.
    cores = os.sysconf("SC_NPROCESSORS_ONLN")
    all_cores = False
    while p.poll() is None and not all_cores:
        all_cores = any(parent_pid(r) != victim and "+WT%d " % cores in coordinator_cmdline(r)
                        for r in renderer_pids(coordinator))
        time.sleep(0.1)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 0, err
    assert all_cores or cores < 2, "the healthy slave never rendered with %d threads" % cores
    # The stopped slave's work went to the healthy one, which nobody took for dead.
    assert "another slave renders it too" in err, err
    assert "silent" not in err, err
    assert_same_frames(out, coordinator_references.frames(SCENE, SLOW))
    assert coordinator.wait_no_processes() == []


def test_stopped_renderer_is_noticed(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    p = coordinator.start(PATIENT + ["--no-fc", "--division", "sequence", "--slaves", "2",
                                     SCENE] + SLOW + ["-o", str(out)])
    wait_for_frames(out, 2, p)
    victim = renderer_pids(coordinator)[0]
    os.kill(victim, signal.SIGSTOP)
    _, err = p.communicate(timeout=120)
    # Its slave kept sending its heartbeat, but the frame never came: copied and done.
    assert p.returncode == 0, err
    assert "another slave renders it too" in err, err
    assert_same_frames(out, coordinator_references.frames(SCENE, SLOW))
    assert coordinator.wait_no_processes() == []


def test_endless_frame_is_reported_and_keep_going_renders_the_rest(
        coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    scene = frame_scene(tmp_path, "endless.pov", "#while (1) #end")
    options = ["+FT", "+W160", "+H120", "+KFI1", "+KFF8"]
    r = coordinator.run(PATIENT + ["--keep-going", "--no-fc", "--division", "sequence",
                                   "--slaves", "2", str(scene)] + options + ["-o", str(out)],
                        cwd=tmp_path, timeout=150)
    # Frame 5 hangs on both slaves: reported with its number and POV-Ray's last words; the
    # other frames are rendered, and the run says it failed.
    assert r.returncode == 1, r.stderr
    assert "frame 5 hangs" in r.stderr and "last words" in r.stderr, r.stderr
    assert "frames without a file (their messages above): 5" in r.stderr, r.stderr
    assert_same_as(out, "endless", coordinator_references.frames(SCENE, options), skip=5)
    assert coordinator.wait_no_processes() == []


def test_a_slow_frame_is_copied_but_completes(coordinator, coordinator_references, tmp_path):
    """A frame far slower than the others (here its parse loops for tens of seconds) passes
    its first deadline like a hung one: it gets a copy, but only a later attempt that also
    outlives the hang deadline (a minute at least) would give it up. It completes."""
    out = tmp_path / "out"
    scene = frame_scene(tmp_path, "slow.pov",
                        "#declare I = 0; #while (I < 18000000) #declare I = I + 1; #end")
    options = ["+FT", "+W160", "+H120", "+KFI1", "+KFF8"]
    r = coordinator.run(PATIENT + ["--no-fc", "--division", "frame", "--slaves", "2", str(scene)]
                        + options + ["-o", str(out)], cwd=tmp_path, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "frame 5 has not finished" in r.stderr, r.stderr  # it did pass its first deadline
    assert "hangs" not in r.stderr, r.stderr
    assert_same_as(out, "slow", coordinator_references.frames(SCENE, options), skip=None)
    assert coordinator.wait_no_processes() == []


def test_scene_error_at_one_frame(coordinator, coordinator_references, tmp_path):
    out = tmp_path / "out"
    scene = frame_scene(tmp_path, "broken5.pov", '#error "frame five is broken"')
    options = ["+FT", "+W160", "+H120", "+KFI1", "+KFF8"]
    args = ["--no-fc", "--division", "frame", "--slaves", "2", str(scene)] + options
    # Without --keep-going the render stops at the error, POV-Ray's message and frame named.
    r = coordinator.run(args + ["-o", str(out)], cwd=tmp_path)
    assert r.returncode == 1
    assert "frame 5" in r.stderr and "frame five is broken" in r.stderr, r.stderr
    shutil.rmtree(out)
    # With it, every other frame is rendered, and frame 5 is listed.
    r = coordinator.run(["--keep-going"] + args + ["-o", str(out)], cwd=tmp_path)
    assert r.returncode == 1, r.stderr
    assert "frame five is broken" in r.stderr, r.stderr
    assert "frames without a file (their messages above): 5" in r.stderr, r.stderr
    assert_same_as(out, "broken5", coordinator_references.frames(SCENE, options), skip=5)
    # The scene fixed, the same command renders what its change touched, without --force.
    scene.write_text(scene.read_text().replace('#error "frame five is broken"', ""))
    r = coordinator.run(["--keep-going"] + args + ["-o", str(out)], cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert_same_as(out, "broken5", coordinator_references.frames(SCENE, options), skip=None)
    assert coordinator.wait_no_processes() == []


# --- a pvmd that does not answer -------------------------------------------------------------

class Freezer:
    """A cgroup-v1 freezer group: its processes hang (state D) as on a dead file server."""

    def __init__(self, name):
        self.path = "/sys/fs/cgroup/freezer/" + name

    def __enter__(self):
        os.mkdir(self.path)
        return self

    def freeze(self, pid):
        with open(self.path + "/cgroup.procs", "w") as f:
            f.write(str(pid))
        with open(self.path + "/freezer.state", "w") as f:
            f.write("FROZEN")

    def __exit__(self, *exc):
        with open(self.path + "/freezer.state", "w") as f:
            f.write("THAWED")
        with open(self.path + "/cgroup.procs") as f:
            for pid in f.read().split():
                os.kill(int(pid), signal.SIGKILL)
        deadline = time.time() + 10
        while time.time() < deadline:
            try:
                os.rmdir(self.path)
                break
            except OSError:
                time.sleep(0.1)


def test_stopped_pvmd_is_named_with_what_to_do(coordinator, tmp_path):
    pvmd = coordinator.start_running_vm()
    os.kill(pvmd, signal.SIGSTOP)
    try:
        r = coordinator.run(["--no-fc", SCENE] + ["+FT", "+W64", "+H48", "+KFI1", "+KFF2"] +
                            ["-o", str(tmp_path / "out")], env={"PVM_ALLOW_ROOT": "1"}, timeout=30)
    finally:
        os.kill(pvmd, signal.SIGKILL)
        os.kill(pvmd, signal.SIGCONT)
    assert r.returncode == 1, r.stderr
    assert "(pid %d, PVM_TMP=%s) is stopped" % (pvmd, coordinator.pvm_tmp) in r.stderr, r.stderr
    assert "kill -CONT %d" % pvmd in r.stderr, r.stderr
    assert len(r.stderr.splitlines()) == 1, r.stderr
    assert coordinator.wait_no_processes() == []


@pytest.mark.skipif(not os.path.isdir("/sys/fs/cgroup/freezer"), reason="needs a cgroup freezer")
@pytest.mark.parametrize("stop", [None, signal.SIGTERM], ids=["bound", "sigterm"])
def test_hung_pvmd_never_hangs_the_master(coordinator, tmp_path, stop):
    pvmd = coordinator.start_running_vm()
    with Freezer("fc-test-" + coordinator.mark):
        Freezer("fc-test-" + coordinator.mark).freeze(pvmd)
        p = coordinator.start(["--no-fc", SCENE, "+FT", "+W64", "+H48", "+KFI1", "+KFF2", "-o",
                               str(tmp_path / "out")], env={"PVM_ALLOW_ROOT": "1"})
        if stop:
            time.sleep(2)       # into the pvmd's silence
            stopped = time.time()
            p.send_signal(stop)
        _, err = p.communicate(timeout=60)
        if stop:
            # Deaf to nothing: the signal ends it at once, though libpvm never returns.
            assert p.returncode == 128 + stop, err
            assert time.time() - stopped < 5, err
            assert "interrupted" in err, err
        else:
            # The call has a bound, and the message says which pvmd and what to do.
            assert p.returncode == 1, err
            assert "pvm_mytid (within 10 s) did not return" in err, err
            assert "the PVM daemon (pid %d" % pvmd in err and "kill %d" % pvmd in err, err
    assert coordinator.wait_no_processes() == []
