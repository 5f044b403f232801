"""scripts/pvm-netns-hosts.sh: clusters of namespace hosts that leave each other alone.

`down` removes only what `up` with the same state directory created, and two clusters can be
up at once (a user's, and a test run's). Needs root, iproute2 and openssh-server; the tests
that bring hosts up are skipped otherwise.
"""
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from fcutil import TOP

SCRIPT = TOP / "scripts" / "pvm-netns-hosts.sh"
CGROUP_CPU = Path("/sys/fs/cgroup/cpu")
CGROUP_CPUSET = Path("/sys/fs/cgroup/cpuset")


def netns_usable():
    if os.geteuid() != 0 or not shutil.which("ip") or not os.path.exists("/usr/sbin/sshd"):
        return False
    return subprocess.run(["ip", "netns", "list"], capture_output=True).returncode == 0


needs_netns = pytest.mark.skipif(not netns_usable(), reason="needs root, ip netns and sshd")


def script(state, *args, timeout=120):
    return subprocess.run([str(SCRIPT), *args], env=dict(os.environ, PVM_NETNS_STATE=str(state)),
                          capture_output=True, text=True, timeout=timeout)


class Cluster:
    """What `env` says about the hosts of one state directory."""

    def __init__(self, state):
        self.state = state
        r = script(state, "env")
        assert r.returncode == 0, r.stderr
        self.env = {}
        for line in r.stdout.splitlines():
            key, _, value = line.replace("export ", "", 1).partition("=")
            self.env[key] = value.strip("'")
        self.hosts = self.env["PVM_NETNS_HOSTS"].split()
        self.master = self.env["PVM_NETNS_MASTER"]
        self.rsh = self.env["PVM_RSH"]

    def answers(self, host):
        """The host name its sshd reports over this cluster's ssh, or None."""
        r = subprocess.run([self.rsh, host, "hostname"], capture_output=True, text=True,
                           timeout=30)
        return r.stdout.strip() if r.returncode == 0 else None

    def open_files(self, host):
        """The soft limit on open files of a session on host (ulimit -Sn), as text."""
        r = subprocess.run([self.rsh, host, "ulimit -Sn"], capture_output=True, text=True,
                           timeout=30)
        assert r.returncode == 0, r.stderr
        return r.stdout.strip()

    def assert_up(self):
        for h in self.hosts:
            assert self.answers(h) == h, f"{h} of {self.state} does not answer"
        for name in [self.master] + self.hosts:
            assert resolve(name), f"{name} of {self.state} no longer resolves"


def resolve(name):
    """The address /etc/hosts gives name, or None."""
    r = subprocess.run(["getent", "hosts", name], capture_output=True, text=True)
    return r.stdout.split()[0] if r.returncode == 0 else None


def namespaces():
    r = subprocess.run(["ip", "netns", "list"], capture_output=True, text=True, check=True)
    return {line.split()[0] for line in r.stdout.splitlines() if line.split()}


def assert_gone(cluster):
    """Nothing of cluster is left on the machine."""
    assert not set(cluster.hosts) & namespaces()
    for name in [cluster.master] + cluster.hosts:
        assert resolve(name) is None, name
    for tree in (CGROUP_CPU, CGROUP_CPUSET):
        assert not [p for p in tree.glob("fc-netns-*") if p.name[len("fc-netns-"):]
                    in cluster.hosts]
    assert not Path(cluster.state).exists()


@pytest.fixture
def states(tmp_path):
    """State directories for a test; whatever is up in them is brought down at the end."""
    made = []

    def new(name):
        made.append(tmp_path / name)
        return made[-1]
    yield new
    for state in made:
        script(state, "down")


@needs_netns
def test_two_clusters_and_down_removes_only_its_own(states):
    a, b, c = states("a"), states("b"), states("c")
    # Two `up`s at once: they must not pick the same names or mix their /etc/hosts edits.
    env = dict(os.environ)
    procs = [subprocess.Popen([str(SCRIPT), "up", "2"] + extra,
                              env=dict(env, PVM_NETNS_STATE=str(state)),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
             for state, extra in ((a, []), (b, ["--half", "2"]))]
    for p in procs:
        err = p.communicate(timeout=120)[1]
        assert p.returncode == 0, err
    first, second = Cluster(a), Cluster(b)
    assert len(first.hosts) == len(second.hosts) == 2
    # Invariant: two clusters share no host name, master name or address.
    names = [first.master] + first.hosts + [second.master] + second.hosts
    assert len(set(names)) == len(names)
    addresses = [resolve(n) for n in names]
    assert None not in addresses and len(set(addresses)) == len(addresses)
    first.assert_up()
    second.assert_up()
    half = CGROUP_CPU / f"fc-netns-{second.hosts[1]}"
    assert (half / "cpu.cfs_quota_us").read_text().strip() == "50000"
    if (CGROUP_CPUSET / "cpuset.cpus").exists():
        # The half-core host is pinned to one processor, and what runs on it stays there;
        # the host without a quota is not pinned.
        pinned = (CGROUP_CPUSET / f"fc-netns-{second.hosts[1]}" / "cpuset.cpus").read_text().strip()
        assert pinned.isdigit()
        r = subprocess.run([second.rsh, second.hosts[1], "grep Cpus_allowed_list /proc/self/status"],
                           capture_output=True, text=True, timeout=30)
        assert r.stdout.split() == ["Cpus_allowed_list:", pinned], r.stdout + r.stderr
        assert not (CGROUP_CPUSET / f"fc-netns-{second.hosts[0]}").exists()

    # `down` of a state directory that never had hosts removes nothing.
    r = script(c, "down")
    assert r.returncode == 0, r.stderr
    first.assert_up()
    second.assert_up()

    # `down` of one cluster leaves the other working.
    r = script(b, "down")
    assert r.returncode == 0, r.stderr
    assert_gone(second)
    assert not half.exists()
    first.assert_up()

    r = script(a, "down")
    assert r.returncode == 0, r.stderr
    assert_gone(first)


@needs_netns
def test_orphaned_cluster_is_removed_exactly(states):
    keep, lost = states("keep"), states("lost")
    for state in (keep, lost):
        r = script(state, "up", "1")
        assert r.returncode == 0, r.stderr
    kept, orphan = Cluster(keep), Cluster(lost)
    # The state directory of a killed run is deleted later (pytest keeps only its last
    # three): its cluster can no longer be brought down by `down`, only by --orphans.
    shutil.rmtree(lost)
    listed = script(keep, "list").stdout
    assert f"state {lost} is gone" in listed and orphan.hosts[0] in listed
    r = script(keep, "down", "--orphans")
    assert r.returncode == 0, r.stderr
    assert_gone(orphan)
    kept.assert_up()


def test_state_directory_not_made_by_up_is_left_alone(tmp_path):
    # A directory someone else owns is never taken over or removed.
    state = tmp_path / "mine"
    state.mkdir()
    (state / "precious").write_text("data\n")
    if os.geteuid() == 0:
        for args in (["up", "1"], ["down"]):
            r = script(state, *args)
            assert r.returncode == 1 and "pvm-netns-hosts.sh: " in r.stderr, (args, r.stderr)
            assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert (state / "precious").read_text() == "data\n"


@pytest.mark.skipif(os.geteuid() != 0, reason="needs root")
@pytest.mark.parametrize("args, message", [
    (["up", "0"], "between 1 and 9 hosts"),
    (["up", "2", "--half", "3"], "no host '3'"),
    (["up", "2", "--half"], "--half needs a host list"),
    (["up", "--bogus"], "unknown argument --bogus"),
    (["down", "everything"], "down takes no arguments"),
])
def test_bad_arguments(tmp_path, args, message):
    state = tmp_path / "state"
    r = script(state, *args)
    assert r.returncode == 1, r.stderr
    assert r.stderr.startswith("pvm-netns-hosts.sh: ") and message in r.stderr, r.stderr
    assert not state.exists()


@needs_netns
@pytest.mark.skipif(not (CGROUP_CPUSET / "cpuset.cpus").exists() or (os.cpu_count() or 1) < 2,
                    reason="needs the cpuset controller and two processors")
def test_full_host_gets_a_processor_of_its_own_half_hosts_share_one(states):
    state = states("pinned")
    r = script(state, "up", "3", "--full", "1", "--half", "2,3")
    assert r.returncode == 0, r.stderr
    cluster = Cluster(state)
    cpus = [(CGROUP_CPUSET / f"fc-netns-{h}" / "cpuset.cpus").read_text().strip()
            for h in cluster.hosts]
    assert all(c.isdigit() for c in cpus), cpus
    assert cpus[1] == cpus[2] != cpus[0]
    # Invariant: a host allows what a stock Debian host does, 1024 open files (or fewer),
    # whatever this machine allows: the pvmd closes that many descriptors per task it spawns.
    for h in cluster.hosts:
        limit = cluster.open_files(h)
        assert limit.isdigit() and int(limit) <= 1024, (h, limit)
    r = script(state, "down")
    assert r.returncode == 0, r.stderr
    assert_gone(cluster)
