#!/bin/sh
# pvm-netns-hosts.sh - several real PVM hosts on one machine, in network namespaces.
#
#   scripts/pvm-netns-hosts.sh up [N] [--half LIST] [--full LIST] [--no-pin]
#                                          create N hosts (default 3)
#   scripts/pvm-netns-hosts.sh down        remove what `up` with this state directory created
#   scripts/pvm-netns-hosts.sh env         print the exports for a shell
#   scripts/pvm-netns-hosts.sh list        list every cluster of this script on the machine
#   scripts/pvm-netns-hosts.sh down --orphans   remove clusters whose state directory is gone
#
# Each host is a network namespace with its own address on a private bridge, its own host
# name (unshare --uts) and an sshd accepting a key kept in the state directory; sshd gives
# every session PVM_ROOT, PVM_ALLOW_ROOT=1 and a per-host PVM_TMP. The master side uses the
# bridge address under a name of its own (the pvmd refuses to add hosts when its own name is
# a loopback address). --half puts the listed hosts' sshd (so their pvmd and tasks) in a
# cgroup-v1 CPU quota of half a core, --full of one core: a cluster of unequal machines, like
# the paper's. LIST is host numbers or names, comma separated: "2,3" or "fch2,fch3".
# Hosts with a quota are also pinned (a cgroup-v1 cpuset) when the machine has the processors:
# a --full host gets one of its own, --half hosts share one two by two. A real machine's
# processes never wait for another machine's, and a host held to one core must not run on
# two at once: the kernel then throttles it for the rest of its 100 ms period (Newton alone on
# a full-core host took 1.07x as long unpinned, medians of 5 runs the same hour). Without
# enough processors, or without the cpuset controller, the hosts are not pinned (a note says
# so); --no-pin: never (to compare with the emulation before the pinning).
#
# Several clusters can be up at once, one per state directory ($PVM_NETNS_STATE, default
# /tmp/pvm-netns). Each `up` takes the first free slot K (0..15) and names everything after it:
#   slot 0:  hosts fch1..fchN   master fcmaster   bridge fcbr0  addresses 10.231.0.x
#   slot K:  hosts fcKh1..fcKhN master fcKmaster  bridge fcbrK  addresses 10.231.K.x
# so a first cluster gets the familiar names and a second one (a test run while a user's
# cluster is up) gets others. `env` says which names this cluster got (PVM_NETNS_HOSTS,
# PVM_NETNS_MASTER) and how many open files a session there may have (PVM_NETNS_OPEN_FILES:
# start the console under that limit too, `ulimit -Sn`, as newton-table does). The CPU
# cgroups are $CGROUP_CPU/fc-netns-<host>, the cpusets $CGROUP_CPUSET/fc-netns-<host>: a
# process joins a host by writing its pid into both.
#
# Then:   eval "$(scripts/pvm-netns-hosts.sh env)"
#         printf 'add %s\nquit\n' "$PVM_NETNS_HOSTS" | pvm -n$PVM_NETNS_MASTER
#         build/bin/fc-master scene.ini +Iscene.pov -o out/      # uses all N+1 hosts
#         echo halt | pvm
#         scripts/pvm-netns-hosts.sh down
#
# `up` records everything it creates (namespaces, veths, bridge, /etc/hosts lines, sshd pid
# files, cgroups) in $STATE/created as it goes, and `down` removes exactly that and nothing
# else: another cluster, or another state directory, is never touched. A failed `up` undoes
# what it did. up and down hold a lock ($LOCK) while they change the machine, so two
# invocations at once do not mix their edits of /etc/hosts or pick the same slot.
# A copy of each record is kept in $REGISTRY/slot-K/: a cluster whose state directory was
# deleted (a killed test run's temporary directory, cleaned up later) can still be removed,
# exactly, with `down --orphans`.
#
# State (keys, configs, per-host PVM_TMP, logs) lives in the state directory, which `up`
# creates (it must not exist, or be empty) and `down` removes. Root only. Only addresses of
# namespaces created here carry traffic.
set -eu

STATE=${PVM_NETNS_STATE:-/tmp/pvm-netns}
case "$STATE" in
    *[[:space:]]*) echo "pvm-netns-hosts.sh: PVM_NETNS_STATE '$STATE' contains white space" >&2
                   exit 1 ;;
    /*) ;;
    *) STATE=$PWD/$STATE ;;     # the ssh wrapper and sshd configs name it from anywhere
esac
CREATED=$STATE/created
LOCK=/run/lock/pvm-netns-hosts.lock
REGISTRY=/run/pvm-netns-hosts           # slot-K/state: its state directory; slot-K/created
NET_PREFIX=10.231
MAX_SLOT=15
MARK_BASE="# pvm-netns-hosts"
CGROUP_CPU=/sys/fs/cgroup/cpu
CGROUP_CPUSET=/sys/fs/cgroup/cpuset
# Open files a session may have on each host, at most: the soft limit a stock Debian host
# gives (systemd's default), not this machine's. The pvmd closes every descriptor up to the
# soft limit, one close() apiece, in each task it spawns: under a sandbox's 20,000 a spawn
# took 4-6 ms of CPU, under 1024 a tenth of a millisecond (coordinator/README.md tells users
# who boot their own virtual machine in a container to lower it the same way).
HOST_OPEN_FILES=1024

die() { echo "pvm-netns-hosts.sh: $*" >&2; exit 1; }
note() { echo "pvm-netns-hosts.sh: $*" >&2; }

# The names of slot $1 (sets prefix, bridge, net, master, mark).
slot_names() {
    if [ "$1" = 0 ]; then prefix=fc; else prefix=fc$1; fi
    bridge=fcbr$1
    net=$NET_PREFIX.$1
    master=${prefix}master
    mark="$MARK_BASE slot $1"
}

lock() {
    [ -d "${LOCK%/*}" ] || LOCK=/tmp/pvm-netns-hosts.lock
    exec 9>>"$LOCK"
    # Held for seconds (while up or down change the machine), never for a cluster's life.
    flock -w 300 9 || die "waited 300 s for $LOCK (another up or down hangs?)"
}

record() {      # kind value: something `down` must remove, written before it is created
    echo "$1 $2" >> "$CREATED"
    echo "$1 $2" >> "$REGISTRY/slot-$slot/created"
}

recorded() {    # kind: its values, in the order they were recorded
    [ -f "$CREATED" ] || return 0
    awk -v k="$1" '$1 == k { sub(/^[^ ]+ /, ""); print }' "$CREATED"
}

# Rewrite /etc/hosts in place (it may be a bind mount, so no rename), without the lines
# that end in exactly this cluster's mark.
hosts_drop() {  # mark
    tmp=$(mktemp)
    awk -v m=" $1" 'length($0) < length(m) || substr($0, length($0) - length(m) + 1) != m' \
        /etc/hosts > "$tmp" || { rm -f "$tmp"; die "cannot read /etc/hosts"; }
    cat "$tmp" > /etc/hosts
    rm -f "$tmp"
}

kill_pids() {   # pids...: TERM, then KILL what is left
    [ $# -gt 0 ] || return 0
    kill "$@" 2>/dev/null || true
    i=0
    while [ $i -lt 20 ]; do
        alive=""
        for p in "$@"; do kill -0 "$p" 2>/dev/null && alive="$alive $p"; done
        [ -n "$alive" ] || return 0
        sleep 0.1
        i=$((i + 1))
    done
    # shellcheck disable=SC2086
    kill -9 $alive 2>/dev/null || true
}

# Remove what $CREATED records, processes first, then the state directory $STATE (unless
# $1 is "keep-state"). Runs under the lock.
teardown() {
    for ns in $(recorded netns); do
        if ip netns list 2>/dev/null | awk '{print $1}' | grep -qx "$ns"; then
            # shellcheck disable=SC2046
            kill_pids $(ip netns pids "$ns" 2>/dev/null)
        fi
    done
    for pidfile in $(recorded sshd); do
        if [ -f "$pidfile" ]; then kill_pids $(cat "$pidfile"); fi
    done
    for cg in $(recorded cgroup); do
        # shellcheck disable=SC2046
        if [ -d "$cg" ]; then kill_pids $(cat "$cg/cgroup.procs" 2>/dev/null); fi
    done
    for ns in $(recorded netns); do
        ip netns del "$ns" 2>/dev/null || true
    done
    # A veth goes with its namespace; one that never got moved into it is deleted here.
    for link in $(recorded veth) $(recorded bridge); do
        ip link del "$link" 2>/dev/null || true
    done
    recorded hosts | while IFS= read -r m; do hosts_drop "$m"; done
    for cg in $(recorded cgroup); do
        if [ -d "$cg" ] && ! rmdir "$cg" 2>/dev/null; then note "cannot remove cgroup $cg"; fi
    done
    for d in $(recorded registry); do
        rm -rf "$d"
    done
    if [ "${1:-}" != keep-state ]; then rm -rf "$STATE"; fi
}

down() {
    if [ ! -f "$CREATED" ]; then
        if [ -d "$STATE" ] && [ -n "$(ls -A "$STATE")" ]; then
            die "$STATE has no record of hosts (no $CREATED): not made by up, nothing removed"
        fi
        note "no hosts are up for $STATE: nothing to remove"
        return 0
    fi
    lock
    if [ ! -f "$CREATED" ]; then    # another down of the same state finished meanwhile
        note "no hosts are up for $STATE: nothing to remove"
        return 0
    fi
    teardown
    note "hosts of $STATE are down"
}

# Clusters whose state directory is gone: nobody can use them (their keys went with it) or
# remove them with `down`. Remove each from the registry's copy of its record.
down_orphans() {
    lock
    removed=0
    for d in "$REGISTRY"/slot-*; do
        [ -f "$d/state" ] || continue
        STATE=$(cat "$d/state")
        [ ! -e "$STATE" ] || continue
        CREATED=$d/created
        note "removing slot ${d##*/slot-} (state directory $STATE is gone)"
        teardown keep-state
        removed=$((removed + 1))
    done
    note "$removed orphaned cluster(s) removed"
}

print_env() {
    [ -f "$STATE/env" ] || die "no hosts are up for $STATE (no $STATE/env)"
    cat "$STATE/env"
}

list() {
    found=""
    for d in "$REGISTRY"/slot-*; do
        [ -f "$d/state" ] || continue
        found=1
        st=$(cat "$d/state")
        hosts=$(awk '$1 == "netns" { printf " %s", $2 }' "$d/created")
        if [ -e "$st" ]; then
            echo "slot ${d##*/slot-}: hosts$hosts; state $st"
        else
            echo "slot ${d##*/slot-}: hosts$hosts; state $st is gone (orphan: '$0 down --orphans')"
        fi
    done
    [ -n "$found" ] || note "no clusters are up"
}

slot_free() {   # slot: true when nothing on the machine uses its names or addresses
    slot_names "$1"
    [ ! -e "$REGISTRY/slot-$1" ] || return 1
    ! ip link show "$bridge" >/dev/null 2>&1 || return 1
    [ -z "$(ip -4 addr show to "$net.0/24" 2>/dev/null)" ] || return 1
    [ -z "$(ip -4 route show to root "$net.0/24" 2>/dev/null)" ] || return 1
    ! ip netns list 2>/dev/null | awk '{print $1}' | grep -q "^${prefix}h[0-9]" || return 1
    ! grep -Eq "[[:space:]](${prefix}h[0-9]+|$master)([[:space:]]|\$)" /etc/hosts || return 1
    for cg in "$CGROUP_CPU/fc-netns-${prefix}h"*; do
        [ ! -e "$cg" ] || return 1
    done
}

expand_cpus() {  # a cpuset list ("0-3,6"): one processor number per line
    echo "$1" | tr ',' '\n' | while IFS=- read -r lo hi; do
        [ -n "$lo" ] || continue
        k=$lo
        while [ "$k" -le "${hi:-$lo}" ]; do echo "$k"; k=$((k + 1)); done
    done
}

# Pin the hosts of $quota_hosts ("N:quota" items): full ones a processor each, half ones two
# to a processor, in the order of the machine's processors.
pin_hosts() {
    [ -f "$CGROUP_CPUSET/cpuset.cpus" ] || { note "no cpuset controller at $CGROUP_CPUSET: hosts not pinned"; return 0; }
    cpus=$(expand_cpus "$(cat "$CGROUP_CPUSET/cpuset.cpus")")
    fulls=""; halves=""
    for item in $quota_hosts; do
        if [ "${item#*:}" = 100000 ]; then fulls="$fulls ${item%%:*}"; else halves="$halves ${item%%:*}"; fi
    done
    nfull=$(echo $fulls | wc -w); nhalf=$(echo $halves | wc -w)
    need=$((nfull + (nhalf + 1) / 2))
    if [ "$need" -gt "$(echo $cpus | wc -w)" ]; then
        note "$need processors needed to pin the hosts, $(echo $cpus | wc -w) here: hosts not pinned"
        return 0
    fi
    set -- $cpus
    assignments=""
    for k in $fulls; do assignments="$assignments $k:$1"; shift; done
    paired=""
    for k in $halves; do
        assignments="$assignments $k:$1"
        if [ -n "$paired" ]; then paired=""; shift; else paired=1; fi
    done
    for item in $assignments; do
        h=${prefix}h${item%%:*}
        new_host_cgroup "$CGROUP_CPUSET" "$h"
        echo "${item#*:}" > "$cg/cpuset.cpus"
        cat "$CGROUP_CPUSET/cpuset.mems" > "$cg/cpuset.mems"
        cat "$STATE/sshd-$h.pid" > "$cg/cgroup.procs"
    done
}

# Make host $2's cgroup in the tree $1 (recorded for `down`) and set cg to it; the caller
# sets it up and then moves the host's sshd in (a cpuset takes no task before its cpus).
new_host_cgroup() {
    cg="$1/fc-netns-$2"
    [ ! -e "$cg" ] || die "cgroup $cg exists already (another cluster's, or left behind)"
    record cgroup "$cg"
    mkdir "$cg"
}

host_number() {  # item n: the host number of a --half/--full item ("2", "fch2", "fc3h2")
    case "$1" in
        *[!0-9]*) k=${1##*h} ;;
        *) k=$1 ;;
    esac
    case "$k" in
        ''|*[!0-9]*) die "no host '$1' (give host numbers 1..$2 or their names)" ;;
    esac
    [ "$k" -ge 1 ] && [ "$k" -le "$2" ] || die "no host '$1' (hosts 1..$2)"
    echo "$k"
}

on_exit_up() {
    status=$?
    if [ -z "${up_done:-}" ]; then
        note "up failed: removing what it created"
        teardown
    fi
    exit "$status"
}

up() {
    n=3
    half=""
    full=""
    pin=1
    while [ $# -gt 0 ]; do
        case "$1" in
            --no-pin) pin=""; shift ;;
            --half|--full)
                [ $# -ge 2 ] || die "$1 needs a host list"
                if [ "$1" = --half ]; then half=$2; else full=$2; fi
                shift 2 ;;
            [0-9]*) n=$1; shift ;;
            *) die "unknown argument $1" ;;
        esac
    done
    case "$n" in *[!0-9]*) die "host count '$n' is not a number" ;; esac
    [ "$n" -ge 1 ] && [ "$n" -le 9 ] || die "between 1 and 9 hosts"
    quota_hosts=""
    for item in $(echo "$half" | tr ',' ' '); do
        quota_hosts="$quota_hosts $(host_number "$item" "$n"):50000"
    done
    for item in $(echo "$full" | tr ',' ' '); do
        quota_hosts="$quota_hosts $(host_number "$item" "$n"):100000"
    done
    if [ -n "$quota_hosts" ] && [ ! -f "$CGROUP_CPU/cpu.cfs_quota_us" ]; then
        die "--half/--full need the cgroup-v1 CPU controller at $CGROUP_CPU"
    fi
    for cmd in ip unshare ssh ssh-keygen flock; do
        command -v $cmd >/dev/null || die "$cmd missing (packages iproute2 util-linux openssh-client)"
    done
    [ -x /usr/sbin/sshd ] || die "/usr/sbin/sshd missing (package openssh-server)"
    [ ! -f "$CREATED" ] || die "hosts of $STATE are already up; run 'PVM_NETNS_STATE=$STATE $0 down' first"
    if [ -d "$STATE" ] && [ -n "$(ls -A "$STATE")" ]; then
        die "state directory $STATE exists and is not empty (set PVM_NETNS_STATE to a new one)"
    fi

    lock
    [ ! -f "$CREATED" ] || die "hosts of $STATE are already up"
    slot=""
    k=0
    while [ $k -le $MAX_SLOT ]; do
        if slot_free $k; then slot=$k; break; fi
        k=$((k + 1))
    done
    [ -n "$slot" ] || die "all $((MAX_SLOT + 1)) slots are in use ('$0 list' shows by whom)"
    slot_names "$slot"

    mkdir -p "$STATE" "$REGISTRY/slot-$slot" /run/sshd
    chmod 700 "$STATE"
    : > "$CREATED"
    echo "$STATE" > "$REGISTRY/slot-$slot/state"
    trap on_exit_up EXIT
    trap 'exit 130' INT TERM HUP
    record slot "$slot"
    record registry "$REGISTRY/slot-$slot"
    mkdir -p "$STATE/master-tmp"
    ssh-keygen -q -t ed25519 -N '' -C pvm-netns-user -f "$STATE/id_ed25519"
    ssh-keygen -q -t ed25519 -N '' -C pvm-netns-host -f "$STATE/hostkey"
    cp "$STATE/id_ed25519.pub" "$STATE/authorized_keys"

    record bridge "$bridge"
    ip link add "$bridge" type bridge
    ip addr add "$net.1/24" dev "$bridge"
    ip link set "$bridge" up
    record hosts "$mark"
    echo "$net.1 $master $mark" >> /etc/hosts

    names=""
    i=1
    while [ $i -le "$n" ]; do
        names="$names ${prefix}h$i"
        i=$((i + 1))
    done
    {
        echo "Host$names"
        echo "    User root"
        echo "    IdentityFile $STATE/id_ed25519"
        echo "    IdentitiesOnly yes"
        echo "    StrictHostKeyChecking no"
        echo "    UserKnownHostsFile /dev/null"
        echo "    LogLevel ERROR"
        echo "    BatchMode yes"
        echo "    ConnectTimeout 5"
    } > "$STATE/ssh_config"
    printf '#!/bin/sh\nexec /usr/bin/ssh -F %s "$@"\n' "$STATE/ssh_config" > "$STATE/rsh"
    chmod 755 "$STATE/rsh"

    i=1
    for h in $names; do
        addr="$net.$((10 + i))"
        record netns "$h"
        ip netns add "$h"
        record veth "$h-br"
        ip link add "$h-br" type veth peer name "$h-ns"
        ip link set "$h-br" master "$bridge" up
        ip link set "$h-ns" netns "$h"
        ip netns exec "$h" ip link set lo up
        ip netns exec "$h" ip addr add "$addr/24" dev "$h-ns"
        ip netns exec "$h" ip link set "$h-ns" up
        echo "$addr $h $mark" >> /etc/hosts
        mkdir -p "$STATE/$h-tmp"
        {
            echo "ListenAddress $addr"
            echo "HostKey $STATE/hostkey"
            echo "PidFile $STATE/sshd-$h.pid"
            echo "AuthorizedKeysFile $STATE/authorized_keys"
            echo "PermitRootLogin prohibit-password"
            echo "PasswordAuthentication no"
            echo "KbdInteractiveAuthentication no"
            echo "UsePAM no"
            echo "StrictModes no"
            echo "SetEnv PVM_ROOT=/usr/lib/pvm3 PVM_ALLOW_ROOT=1 PVM_TMP=$STATE/$h-tmp"
        } > "$STATE/sshd-$h.conf"
        record sshd "$STATE/sshd-$h.pid"
        # 9>&-: the daemon must not inherit the lock, or it would hold it for its whole life.
        # The sshd's limits are its sessions', so the pvmd's and its tasks'.
        ip netns exec "$h" unshare --uts sh -c \
            "hostname $h && $(lower_open_files) && exec /usr/sbin/sshd -f $STATE/sshd-$h.conf -E $STATE/sshd-$h.log" 9>&-
        i=$((i + 1))
    done

    # Wait until every sshd answers with its own host name.
    for h in $names; do
        ok=""
        k=0
        while [ $k -lt 50 ]; do
            if [ "$("$STATE/rsh" "$h" hostname 2>/dev/null 9>&-)" = "$h" ]; then ok=1; break; fi
            sleep 0.1
            k=$((k + 1))
        done
        [ -n "$ok" ] || die "sshd on $h does not answer (see $STATE/sshd-$h.log)"
    done

    for item in $quota_hosts; do
        h=${prefix}h${item%%:*}
        new_host_cgroup "$CGROUP_CPU" "$h"
        echo 100000 > "$cg/cpu.cfs_period_us"
        echo "${item#*:}" > "$cg/cpu.cfs_quota_us"
        cat "$STATE/sshd-$h.pid" > "$cg/cgroup.procs"
    done
    [ -z "$quota_hosts" ] || [ -z "$pin" ] || pin_hosts

    {
        echo "export PVM_ROOT=/usr/lib/pvm3"
        echo "export PVM_ALLOW_ROOT=1"
        echo "export PVM_RSH=$STATE/rsh"
        echo "export PVM_TMP=$STATE/master-tmp"
        echo "export PVM_NETNS_STATE=$STATE"
        echo "export PVM_NETNS_MASTER=$master"
        echo "export PVM_NETNS_HOSTS='$(echo $names)'"
        echo "export PVM_NETNS_OPEN_FILES=$HOST_OPEN_FILES"
    } > "$STATE/env"
    up_done=1
    echo "pvm-netns-hosts.sh: hosts$names up; master name $master; state in $STATE" >&2
}

root() { [ "$(id -u)" = 0 ] || die "must run as root (network namespaces, sshd)"; }

# Shell code that lowers the soft limit on open files to HOST_OPEN_FILES (never raises it).
lower_open_files() {
    echo "{ s=\$(ulimit -Sn); if [ \"\$s\" = unlimited ] || [ \"\$s\" -gt $HOST_OPEN_FILES ]; then ulimit -Sn $HOST_OPEN_FILES; fi; }"
}

case "${1:-}" in
    up) shift; root; up "$@" ;;
    down)
        root
        case "$*" in
            down) down ;;
            "down --orphans") down_orphans ;;
            *) die "down takes no arguments but --orphans (it removes what $CREATED records)" ;;
        esac ;;
    env) print_env ;;
    list) list ;;
    *) echo "usage: $0 up [N] [--half LIST] [--full LIST] | down [--orphans] | env | list" >&2
       exit 2 ;;
esac
