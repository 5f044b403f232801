"""Shared pytest fixtures. The coordinator_* helpers serve tests/test_coordinator*.py.

The coordinator tests run the real fc-master, which starts a real private pvmd and real
fc-slave tasks. Every process of one run carries a marker in its environment (inherited
master -> pvmd -> slaves -> renderer), so a test can prove that nothing is left behind and can
kill exactly its own processes, by pid, even when it fails.
"""
import json
import os
import signal
import subprocess
import time
import uuid

import numpy as np
import pytest

from fcutil import files_below

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BIN = os.path.join(TOP, "build", "bin")
COORDINATOR_SCENES = os.path.join(TOP, "scenes", "coordinator-test")
FC_MASTER = os.path.join(BIN, "fc-master")
FC_SLAVE = os.path.join(BIN, "fc-slave")
MARK_VAR = "FC_TEST_MARK"


def coordinator_renderer():
    """The renderer the coordinator tests use: $FC_TEST_POVRAY, our build, else Debian's."""
    env = os.environ.get("FC_TEST_POVRAY")
    if env:
        return env
    ours = os.path.join(BIN, "povray-fc")
    return ours if os.access(ours, os.X_OK) else "/usr/bin/povray"


def master_with_failing_image_writer(tmp_path):
    """A copy of fc-master in a directory of its own whose fc-image-writer fails (fc-master
    finds fc-slave and its helpers beside itself); returns the copy's path."""
    bindir = tmp_path / "bin"
    bindir.mkdir()
    subprocess.run(["cp", FC_MASTER, str(bindir / "fc-master")], check=True)
    for name in ("fc-slave", "fc-image.so"):
        os.symlink(os.path.join(os.path.dirname(FC_MASTER), name), bindir / name)
    writer = bindir / "fc-image-writer"
    writer.write_text("#!/bin/sh\necho 'cannot encode today' >&2\nexit 1\n")
    writer.chmod(0o755)
    return bindir / "fc-master"


def process_mark(pid):
    """The FC_TEST_MARK in a process's environment: None when it has none, or is gone."""
    try:
        with open("/proc/%d/environ" % pid, "rb") as f:
            env = f.read().split(b"\0")
    except OSError:
        return None
    prefix = MARK_VAR.encode() + b"="
    return next((v[len(prefix):].decode(errors="replace") for v in env if v.startswith(prefix)),
                None)


def coordinator_marked_pids(mark):
    """Pids of live processes whose environment carries FC_TEST_MARK=mark."""
    pids = []
    for name in os.listdir("/proc"):
        if not name.isdigit() or int(name) == os.getpid() or process_mark(int(name)) != mark:
            continue
        try:
            with open("/proc/%s/stat" % name) as f:
                state = f.read().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z":
            pids.append(int(name))
    return pids


def parent_pid(pid):
    try:
        with open("/proc/%d/stat" % pid) as f:
            return int(f.read().rsplit(")", 1)[1].split()[1])
    except OSError:
        return 0


def coordinator_cmdline(pid):
    try:
        with open("/proc/%d/cmdline" % pid, "rb") as f:
            return f.read().replace(b"\0", b" ").decode(errors="replace")
    except OSError:
        return ""


def load_rgb(path, pixel_type="uint8"):
    """RGB pixels of an image file as a numpy array (height, width, 3), read as pixel_type
    ("uint8", "uint16", "half": the samples as stored, for 16-bit PNG and OpenEXR)."""
    import OpenImageIO as oiio
    inp = oiio.ImageInput.open(str(path))
    assert inp, "cannot open %s: %s" % (path, oiio.geterror())
    pixels = inp.read_image(0, 0, 0, 3, pixel_type)
    error = inp.geterror()
    inp.close()
    assert pixels is not None and not error, "cannot read %s: %s" % (path, error)
    return np.asarray(pixels)


def renderers_and_coordinators():
    """Lines "pid FC_TEST_MARK cmdline" of the live povray and fc-* processes."""
    lines = []
    for name in os.listdir("/proc"):
        if not name.isdigit():
            continue
        cmdline = coordinator_cmdline(int(name))
        if "povray" in cmdline or "fc-" in cmdline:
            lines.append("%s %s %s" % (name, process_mark(int(name)) or "-", cmdline[:300]))
    return lines


@pytest.fixture(autouse=True)
def scenes_stay_as_checked_out():
    """A renderer given no output name writes its frames into its working directory, which is
    the checkout's scenes for the coordinator tests. A test after which a file appeared there
    fails at its teardown, naming the file and what still runs (a renderer left over from an
    earlier test carries that test's FC_TEST_MARK); the file is removed, so that later tests,
    which copy the scenes, see them as checked out."""
    scenes = os.path.join(TOP, "scenes")
    before = files_below(scenes)
    yield
    added = [os.path.join(scenes, f) for f in sorted(files_below(scenes) - before)]
    if not added:
        return
    described = []
    for path in added:
        try:
            st = os.stat(path)
            described.append("%s (%d bytes, written %s)" % (
                path, st.st_size, time.strftime("%H:%M:%S", time.localtime(st.st_mtime))))
            os.unlink(path)
        except OSError as e:
            described.append("%s (%s)" % (path, e))
    pytest.fail("written into the checkout's scenes: %s; now %s; still running:\n%s" % (
        ", ".join(described), time.strftime("%H:%M:%S"),
        "\n".join(renderers_and_coordinators()) or "(none)"))


# What fc-master keeps in an output directory besides the frames.
FC_MASTER_FILES = {".fc-master", "preview"}


def frame_files(outdir):
    """The names in an output directory that are not fc-master's own bookkeeping (its record
    of the run and the preview), sorted."""
    return sorted(f for f in os.listdir(outdir) if f not in FC_MASTER_FILES)


class CoordinatorRun:
    """Runs fc-master with a private PVM_TMP and a process marker; cleans up after itself."""

    def __init__(self, tmp_path):
        self.tmp_path = tmp_path
        self.mark = uuid.uuid4().hex
        self.pvm_tmp = tmp_path / "pvm-tmp"
        self.pvm_tmp.mkdir(exist_ok=True)
        # Protocol trace of the master and its slaves, shown when a run hangs.
        self.debug_log = tmp_path / "fc-debug.log"
        self.procs = []

    def env(self, extra=None):
        env = dict(os.environ)
        env[MARK_VAR] = self.mark
        # A private, empty PVM_TMP: the master never joins a virtual machine it does not own
        # unless a test starts one there on purpose.
        env["PVM_TMP"] = str(self.pvm_tmp)
        env.pop("PVM_EXPORT", None)
        env["FC_DEBUG_LOG"] = str(self.debug_log)
        if extra:
            env.update(extra)
        return env

    def argv(self, args, renderer=True, prefix=(), master=FC_MASTER):
        argv = list(prefix) + [str(master)]
        if renderer:
            argv += ["--povray", coordinator_renderer()]
        return argv + list(args)

    def run(self, args, cwd=COORDINATOR_SCENES, timeout=90, renderer=True, env=None, prefix=()):
        """Run fc-master to completion (under the command prefix, if any); returns
        CompletedProcess (text output). A run that does not end in time is interrupted and
        reported with its protocol trace."""
        argv = self.argv(args, renderer, prefix)
        p = subprocess.Popen(argv, cwd=cwd, env=self.env(env), stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
        self.procs.append(p)
        try:
            out, err = p.communicate(timeout=timeout)
        except subprocess.TimeoutExpired:
            procs = [coordinator_cmdline(pid) for pid in self.pids()]
            p.send_signal(signal.SIGINT)
            try:
                out, err = p.communicate(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
                out, err = p.communicate()
            raise AssertionError(
                "fc-master did not finish within %d s: %s\n--- stderr:\n%s\n--- processes:\n%s"
                "\n--- protocol trace (last lines):\n%s"
                % (timeout, " ".join(argv), err[-4000:], "\n".join(procs), self.trace(80)))
        return subprocess.CompletedProcess(argv, p.returncode, out, err)

    def start_running_vm(self):
        """A virtual machine running in this run's PVM_TMP, started with the console as a user
        starts one; returns its pvmd's pid."""
        env = self.env({"PVM_ALLOW_ROOT": "1"})
        started = subprocess.run(["pvm"], input="quit\n", env=env, capture_output=True,
                                 text=True, timeout=30)
        assert "pvmd still running" in started.stdout + started.stderr, started
        # The pvmd may briefly fork a helper (pvmd'); the daemon is the one whose parent is not.
        pvmds = [p for p in self.pids() if os.path.basename(
            coordinator_cmdline(p).split(" ")[0]) == "pvmd"]
        pvmds = [p for p in pvmds if parent_pid(p) not in pvmds]
        assert len(pvmds) == 1, [coordinator_cmdline(p) for p in self.pids()]
        return pvmds[0]

    def trace(self, lines=60):
        """The last lines of the protocol trace (FC_DEBUG_LOG)."""
        try:
            with open(self.debug_log) as f:
                return "".join(f.readlines()[-lines:])
        except OSError:
            return "(no trace)"

    def start(self, args, cwd=COORDINATOR_SCENES, renderer=True, env=None, prefix=()):
        """Start fc-master in the background (under the command prefix, if any); returns
        the Popen."""
        p = subprocess.Popen(self.argv(args, renderer, prefix), cwd=cwd, env=self.env(env),
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.procs.append(p)
        return p

    def pids(self):
        return coordinator_marked_pids(self.mark)

    def wait_no_processes(self, timeout=10):
        """Wait until no marked process is left; returns the command lines of survivors."""
        deadline = time.time() + timeout
        while time.time() < deadline:
            pids = self.pids()
            if not pids:
                return []
            time.sleep(0.1)
        return [coordinator_cmdline(p) or str(p) for p in self.pids()]

    def cleanup(self):
        for p in self.procs:
            if p.poll() is None:
                p.kill()
            try:
                p.communicate(timeout=5)
            except Exception:
                pass
        for _ in range(3):
            pids = self.pids()
            if not pids:
                break
            for pid in pids:
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
            time.sleep(0.2)


@pytest.fixture
def coordinator(tmp_path):
    """A CoordinatorRun for one test; kills whatever the test left behind, even on failure."""
    run = CoordinatorRun(tmp_path)
    yield run
    run.cleanup()


@pytest.fixture(scope="session")
def coordinator_build():
    """Build fc-master and fc-slave (fast when up to date)."""
    r = subprocess.run(["make", "-C", TOP, "coordinator"], capture_output=True, text=True)
    assert r.returncode == 0, "building the coordinator failed:\n" + r.stdout + r.stderr
    assert os.access(FC_MASTER, os.X_OK) and os.access(FC_SLAVE, os.X_OK)
    return BIN


class CoordinatorReferences:
    """Single-process renders of the same frames, rendered once per session and reused."""

    def __init__(self, root):
        self.root = root
        self.cache = {}
        self.dirs = {}

    def path(self, scene, options, name):
        """The file `name` of the reference render of `scene` with `options` (rendered first
        with frames())."""
        return self.dirs[(scene, tuple(options))] / name

    def frames(self, scene, options, pixel_type="uint8"):
        """Render `scene` with `options` in one POV-Ray process (Targa unless the options name
        another format); returns {file name: pixels read as pixel_type}."""
        key = (scene, tuple(options), pixel_type)
        if key not in self.cache:
            out = self.root / ("ref%d" % len(self.cache))
            self.dirs[(scene, tuple(options))] = out
            out.mkdir()
            stem = os.path.splitext(os.path.basename(scene))[0]
            argv = [coordinator_renderer(), scene, "-D", "+FT", "-UA",
                    "+O%s/%s" % (out, stem)] + list(options)
            r = subprocess.run(argv, cwd=COORDINATOR_SCENES, capture_output=True, text=True,
                               timeout=300)
            assert r.returncode == 0, "reference render failed:\n" + r.stderr[-3000:]
            self.cache[key] = {f: load_rgb(str(out / f), pixel_type)
                               for f in sorted(os.listdir(out))}
        return self.cache[key]


@pytest.fixture(scope="session")
def coordinator_references(tmp_path_factory):
    return CoordinatorReferences(tmp_path_factory.mktemp("coordinator-references"))


def coordinator_stats(path):
    with open(path) as f:
        return json.load(f)
