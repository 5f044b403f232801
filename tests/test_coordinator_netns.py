"""fc-master on several real PVM hosts: network namespaces with their own sshd and pvmd.

scripts/pvm-netns-hosts.sh creates three hosts (one machine, separate network namespaces,
host names and PVM_TMPs): fch1..fch3 with a master name fcmaster, or other names when another
cluster is up (its `env` says which); the tests start the master pvmd under the master name,
add hosts with the PVM console, and run fc-master in the running virtual machine. Needs root,
iproute2 and openssh-server; skipped otherwise.
"""
import os
import shutil
import signal
import subprocess
import time

import pytest

from conftest import TOP, coordinator_stats, frame_files, load_rgb
from fcutil import LONG_COORDINATOR_RENDER

pytestmark = pytest.mark.usefixtures("coordinator_build")

SCRIPT = os.path.join(TOP, "scripts", "pvm-netns-hosts.sh")
SCENE = "moving.pov"
OPTS = ["+FT", "+W160", "+H120", "+KFI1", "+KFF12"]
SLOW = ["+FT", "+W320", "+H240", "+KFI1", "+KFF24", "+A0.1", "+AM2", "+R3"]


def netns_usable():
    if os.geteuid() != 0 or not shutil.which("ip") or not os.path.exists("/usr/sbin/sshd"):
        return False
    r = subprocess.run(["ip", "netns", "list"], capture_output=True)
    return r.returncode == 0


pytestmark = [pytestmark, pytest.mark.skipif(not netns_usable(),
                                             reason="needs root, ip netns and sshd")]


def netns_pids(host):
    r = subprocess.run(["ip", "netns", "pids", host], capture_output=True, text=True)
    return [int(p) for p in r.stdout.split()]


def program(pid):
    """The process's program name (sshd rewrites its argv, so not from the command line)."""
    try:
        with open("/proc/%d/comm" % pid) as f:
            return f.read().strip()
    except OSError:
        return ""


@pytest.fixture(scope="module")
def netns_hosts(tmp_path_factory):
    """Three hosts for this module; their environment (PVM_RSH, PVM_TMP, PVM_NETNS_HOSTS...).

    A fresh state directory: `down` at the end removes these hosts and nothing else, so a
    user's cluster or another test run's stays up."""
    state = str(tmp_path_factory.mktemp("pvm-netns") / "state")
    env = dict(os.environ, PVM_NETNS_STATE=state)
    r = subprocess.run([SCRIPT, "up", "3"], env=env, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    exports = {}
    for line in subprocess.run([SCRIPT, "env"], env=env, capture_output=True,
                               text=True).stdout.splitlines():
        key, _, value = line.replace("export ", "", 1).partition("=")
        exports[key] = value.strip("'")
    yield exports
    r = subprocess.run([SCRIPT, "down"], env=env, capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr


class VirtualMachine:
    """A PVM virtual machine over the namespace hosts, started with the console."""

    def __init__(self, coordinator, hosts):
        self.coordinator = coordinator
        self.env = dict(hosts)
        # Remote slaves get the test's process marker and the protocol trace file too.
        self.env["PVM_EXPORT"] = "FC_TEST_MARK:FC_DEBUG_LOG"
        self.hosts = hosts["PVM_NETNS_HOSTS"].split()
        for d in [hosts["PVM_TMP"]] + [os.path.join(os.path.dirname(hosts["PVM_TMP"]),
                                                    h + "-tmp") for h in self.hosts]:
            for f in os.listdir(d):
                os.unlink(os.path.join(d, f))

    def console(self, commands, timeout=60):
        r = subprocess.run(["pvm", "-n" + self.env["PVM_NETNS_MASTER"]],
                           input="".join(c + "\n" for c in commands + ["quit"]),
                           env=self.coordinator.env(self.env), capture_output=True, text=True,
                           timeout=timeout)
        return r.stdout + r.stderr

    def add(self, hosts, total):
        """Add hosts and wait until the machine has `total` hosts."""
        added = self.console(["add " + " ".join(hosts)])
        self.wait_hosts(total, added)

    def wait_hosts(self, n, added="", timeout=30):
        deadline = time.time() + timeout
        while time.time() < deadline:
            out = self.console(["conf"])
            if "%d hosts" % n in out:
                return
            time.sleep(0.3)
        raise AssertionError("virtual machine does not have %d hosts:\n%s\n%s" % (n, added, out))

    def stop(self):
        try:
            self.console(["halt"], timeout=5)
        except subprocess.TimeoutExpired:
            pass    # a crashed host can hold up halt; what is left is killed below
        # Remote pvmds were started over ssh: stop what is left in the namespaces by pid.
        for h in self.hosts:
            for pid in netns_pids(h):
                if program(pid) != "sshd":
                    try:
                        os.kill(pid, signal.SIGKILL)
                    except OSError:
                        pass


@pytest.fixture
def vm(coordinator, netns_hosts):
    machine = VirtualMachine(coordinator, netns_hosts)
    yield machine
    machine.stop()


def finish(coordinator, p, timeout=120):
    """Wait for a background fc-master; on a hang show its output and protocol trace."""
    try:
        return p.communicate(timeout=timeout)[1]
    except subprocess.TimeoutExpired:
        p.send_signal(signal.SIGINT)
        try:
            err = p.communicate(timeout=15)[1]
        except subprocess.TimeoutExpired:
            p.kill()
            err = p.communicate()[1]
        raise AssertionError("fc-master hung:\n%s\n--- trace:\n%s" % (err, coordinator.trace(150)))


def wait_for_renderer(host, p):
    """Wait until a renderer runs on host (fc-master p still running), and half a second more:
    the host is then in the middle of its work."""
    deadline = time.time() + 60
    while not any(program(x) in ("povray-fc", "povray") for x in netns_pids(host)):
        assert time.time() < deadline and p.poll() is None, "no renderer on " + host
        time.sleep(0.05)
    time.sleep(0.5)


def assert_same(outdir, reference):
    assert frame_files(outdir) == sorted(reference)
    for name, want in reference.items():
        got = load_rgb(os.path.join(outdir, name))
        # Invariant: frames rendered on several hosts equal the single-process render.
        assert (got == want).all(), name


@pytest.mark.parametrize("division", ["sequence", "frame"])
def test_all_hosts_render(coordinator, coordinator_references, vm, tmp_path, division):
    vm.add(vm.hosts, 4)
    out, stats = tmp_path / "out", tmp_path / "stats.json"
    r = coordinator.run(["--no-fc", "--quiet", "--division", division, "--stats", str(stats),
                         SCENE] + OPTS + ["-o", str(out)], env=vm.env)
    assert r.returncode == 0, r.stderr + coordinator.trace()
    assert_same(out, coordinator_references.frames(SCENE, OPTS))
    s = coordinator_stats(stats)
    assert s["virtual_machine"] == "running" and s["hosts_used"] == 4
    # Invariant: every host got slaves (one per core) and rendered something.
    names = {h["name"]: h for h in s["hosts"]}
    assert set(names) == {vm.env["PVM_NETNS_MASTER"]} | set(vm.hosts)
    for h in names.values():
        assert h["slaves"] >= 1 and h["jobs"] >= 1, s["hosts"]
    # No slave is left on any host once the master is done.
    deadline = time.time() + 10
    while time.time() < deadline and any(program(p) == "fc-slave" for h in vm.hosts
                                         for p in netns_pids(h)):
        time.sleep(0.1)
    assert not any(program(p) == "fc-slave" for h in vm.hosts for p in netns_pids(h))


def test_crashed_host_work_is_requeued(coordinator, coordinator_references, vm, tmp_path):
    vm.add(vm.hosts, 4)
    out = tmp_path / "out"
    crashed = vm.hosts[1]
    p = coordinator.start(["--no-fc", "--timeout", "5", "--division", "sequence", SCENE] +
                          SLOW + ["-o", str(out)], env=vm.env)
    wait_for_renderer(crashed, p)
    # The host crashes: its pvmd, slaves and renderers vanish at once.
    for pid in netns_pids(crashed):
        if program(pid) != "sshd":
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass    # it ended between the listing and the kill (a renderer done)
    err = finish(coordinator, p)
    assert p.returncode == 0, err + coordinator.trace()
    # Invariant: every frame of the crashed host arrives, from another host. (Whether the
    # master first times the host out, "on <host> was silent", or an idle slave duplicates
    # its unit and finishes it first depends on timing, so neither message is required.)
    assert_same(out, coordinator_references.frames(SCENE, SLOW))


def test_host_added_while_rendering(coordinator, coordinator_references, vm, tmp_path):
    first, late = vm.hosts[0], vm.hosts[2]
    vm.add([first], 2)
    out, stats = tmp_path / "out", tmp_path / "stats.json"
    p = coordinator.start(["--no-fc", "--division", "frame", "--stats", str(stats), SCENE] +
                          LONG_COORDINATOR_RENDER + ["-o", str(out)], env=vm.env)
    time.sleep(1.0)
    assert p.poll() is None
    vm.console(["add " + late])
    err = finish(coordinator, p)
    assert p.returncode == 0, err + coordinator.trace()
    assert "host %s joined" % late in err
    assert_same(out, coordinator_references.frames(SCENE, LONG_COORDINATOR_RENDER))
    hosts = {h["name"]: h for h in coordinator_stats(stats)["hosts"]}
    # Invariant: a host added while rendering gets slaves and work.
    assert hosts[late]["jobs"] >= 1, hosts


def test_host_deleted_and_added_again_counts_once(coordinator, coordinator_references, vm,
                                                  tmp_path):
    vm.add(vm.hosts, 4)
    out, stats = tmp_path / "out", tmp_path / "stats.json"
    again = vm.hosts[2]
    p = coordinator.start(["--no-fc", "--division", "frame", "--stats", str(stats), SCENE] +
                          SLOW + ["-o", str(out)], env=vm.env)
    time.sleep(1.0)
    assert p.poll() is None
    vm.console(["delete " + again])
    vm.wait_hosts(3)
    vm.console(["add " + again])
    err = finish(coordinator, p)
    assert p.returncode == 0, err + coordinator.trace()
    assert_same(out, coordinator_references.frames(SCENE, SLOW))
    # Invariant: a host that left and came back is one host, in the summary and the stats.
    assert "4 host(s)" in err, err
    assert coordinator_stats(stats)["hosts_used"] == 4


def test_private_machine_from_hostfile(coordinator, coordinator_references, netns_hosts,
                                       tmp_path):
    # No machine running: fc-master starts its own pvmd with the hosts of a host file and
    # halts all of them at the end.
    hostfile = tmp_path / "hosts"
    hosts = netns_hosts["PVM_NETNS_HOSTS"].split()
    hostfile.write_text("".join(h + "\n" for h in hosts))
    env = dict(netns_hosts, PVM_EXPORT="FC_TEST_MARK:FC_DEBUG_LOG")
    env["PVM_TMP"] = str(coordinator.pvm_tmp)       # empty: nothing to join
    out, stats = tmp_path / "out", tmp_path / "stats.json"
    r = coordinator.run(["--no-fc", "--quiet", "--hostfile", str(hostfile), "--pvmd-name",
                         netns_hosts["PVM_NETNS_MASTER"], "--stats", str(stats), SCENE] + OPTS +
                        ["-o", str(out)], env=env)
    assert r.returncode == 0, r.stderr + coordinator.trace()
    assert_same(out, coordinator_references.frames(SCENE, OPTS))
    s = coordinator_stats(stats)
    assert s["virtual_machine"] == "private" and s["hosts_used"] == 1 + len(hosts)
    # Invariant: the private machine is gone everywhere: no pvmd or slave on any host.
    deadline = time.time() + 10
    while time.time() < deadline and any(program(p) != "sshd" for h in hosts
                                         for p in netns_pids(h)):
        time.sleep(0.1)
    assert [program(p) for h in hosts for p in netns_pids(h)] == ["sshd"] * len(hosts)
    assert coordinator.wait_no_processes() == []


@pytest.mark.parametrize("fault", ["stopped-host", "killed-pvmd"])
def test_lost_host_work_is_copied_without_waiting(coordinator, coordinator_references, vm,
                                                  tmp_path, fault):
    # With a --timeout far beyond the test's bound, only the progress rules can finish the
    # run in time: the lost host's jobs pass their deadline and are copied to other hosts.
    vm.add(vm.hosts, 4)
    out = tmp_path / "out"
    lost = vm.hosts[1]
    p = coordinator.start(["--no-fc", "--timeout", "600", "--division", "frame", SCENE] +
                          SLOW + ["-o", str(out)], env=vm.env)
    wait_for_renderer(lost, p)
    victims = [pid for pid in netns_pids(lost)
               if program(pid) != "sshd" and (fault == "stopped-host" or program(pid) == "pvmd")]
    for pid in victims:
        try:
            os.kill(pid, signal.SIGSTOP if fault == "stopped-host" else signal.SIGKILL)
        except ProcessLookupError:
            pass
    try:
        err = finish(coordinator, p, timeout=150)
    finally:
        for pid in victims:
            try:
                os.kill(pid, signal.SIGCONT)
            except ProcessLookupError:
                pass
    assert p.returncode == 0, err + coordinator.trace()
    assert "another slave renders it too" in err, err
    # No slave of a healthy host was taken for lost.
    assert "silent" not in err, err
    assert_same(out, coordinator_references.frames(SCENE, SLOW))
