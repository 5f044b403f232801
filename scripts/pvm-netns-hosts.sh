#!/bin/sh
# pvm-netns-hosts.sh - several real PVM hosts on one machine, in network namespaces.
#
#   scripts/pvm-netns-hosts.sh up [N] [--half HOST,...]   create hosts fch1..fchN (default 3)
#   scripts/pvm-netns-hosts.sh down                       remove everything `up` created
#   scripts/pvm-netns-hosts.sh env                        print the exports for a shell
#
# Each host is a network namespace with its own address (10.231.0.1x on a private bridge),
# its own host name (unshare --uts) and an sshd accepting a key kept in the state directory;
# sshd gives every session PVM_ROOT, PVM_ALLOW_ROOT=1 and a per-host PVM_TMP. The master side
# uses the bridge address under the name fcmaster (the pvmd refuses to add hosts when its own
# name is a loopback address). --half puts the named hosts' sshd (so their pvmd and tasks) in
# a cgroup-v1 CPU quota of half a core: a cluster of unequal machines, like the paper's.
#
# Then:   eval "$(scripts/pvm-netns-hosts.sh env)"
#         printf 'add fch1 fch2 fch3\nquit\n' | pvm -nfcmaster
#         build/bin/fc-master scene.ini -o out/      # uses all four hosts
#         echo halt | pvm
#
# State (keys, configs, per-host PVM_TMP, logs) lives in $PVM_NETNS_STATE (default
# /tmp/pvm-netns). Root only. Only addresses of namespaces created here carry traffic; /etc/hosts
# lines added here end with "# pvm-netns-hosts" and are removed by `down`.
set -eu

STATE=${PVM_NETNS_STATE:-/tmp/pvm-netns}
BRIDGE=fcbr0
NET=10.231.0
MASTER_NAME=fcmaster
MARK="# pvm-netns-hosts"
CGROUP_CPU=/sys/fs/cgroup/cpu

die() { echo "pvm-netns-hosts.sh: $*" >&2; exit 1; }

[ "$(id -u)" = 0 ] || die "must run as root (network namespaces, sshd)"

# Rewrite /etc/hosts in place (it may be a bind mount, so no rename).
hosts_drop_ours() {
    tmp=$(mktemp)
    grep -v "$MARK\$" /etc/hosts > "$tmp" || true
    cat "$tmp" > /etc/hosts
    rm -f "$tmp"
}

hosts_add() {   # address name
    echo "$1 $2 $MARK" >> /etc/hosts
}

our_namespaces() {
    ip netns list 2>/dev/null | awk '{print $1}' | grep '^fch[0-9][0-9]*$' || true
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

down() {
    for ns in $(our_namespaces); do
        # shellcheck disable=SC2046
        kill_pids $(ip netns pids "$ns")
        ip netns del "$ns"
    done
    ip link del "$BRIDGE" 2>/dev/null || true
    hosts_drop_ours
    for cg in "$CGROUP_CPU"/fc-netns-*; do
        [ -d "$cg" ] || continue
        # shellcheck disable=SC2046
        kill_pids $(cat "$cg/cgroup.procs" 2>/dev/null)
        rmdir "$cg" 2>/dev/null || true
    done
    rm -rf "$STATE"
}

print_env() {
    [ -f "$STATE/env" ] || die "no hosts are up (no $STATE/env)"
    cat "$STATE/env"
}

up() {
    n=3
    half=""
    while [ $# -gt 0 ]; do
        case "$1" in
            --half) [ $# -ge 2 ] || die "--half needs a host list"; half=$2; shift 2 ;;
            [0-9]*) n=$1; shift ;;
            *) die "unknown argument $1" ;;
        esac
    done
    [ "$n" -ge 1 ] && [ "$n" -le 9 ] || die "between 1 and 9 hosts"
    [ -z "$(our_namespaces)" ] || die "hosts are already up; run '$0 down' first"
    for cmd in ip unshare ssh ssh-keygen; do
        command -v $cmd >/dev/null || die "$cmd missing (packages iproute2 util-linux openssh-client)"
    done
    [ -x /usr/sbin/sshd ] || die "/usr/sbin/sshd missing (package openssh-server)"

    rm -rf "$STATE"
    mkdir -p "$STATE/master-tmp" /run/sshd
    chmod 700 "$STATE"
    ssh-keygen -q -t ed25519 -N '' -C pvm-netns-user -f "$STATE/id_ed25519"
    ssh-keygen -q -t ed25519 -N '' -C pvm-netns-host -f "$STATE/hostkey"
    cp "$STATE/id_ed25519.pub" "$STATE/authorized_keys"

    ip link add "$BRIDGE" type bridge
    ip addr add "$NET.1/24" dev "$BRIDGE"
    ip link set "$BRIDGE" up
    hosts_add "$NET.1" "$MASTER_NAME"

    {
        echo "Host fch*"
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

    names=""
    i=1
    while [ $i -le "$n" ]; do
        h=fch$i
        addr="$NET.$((10 + i))"
        ip netns add "$h"
        ip link add "$h-br" type veth peer name "$h-ns"
        ip link set "$h-br" master "$BRIDGE" up
        ip link set "$h-ns" netns "$h"
        ip netns exec "$h" ip link set lo up
        ip netns exec "$h" ip addr add "$addr/24" dev "$h-ns"
        ip netns exec "$h" ip link set "$h-ns" up
        hosts_add "$addr" "$h"
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
        ip netns exec "$h" unshare --uts sh -c \
            "hostname $h && exec /usr/sbin/sshd -f $STATE/sshd-$h.conf -E $STATE/sshd-$h.log"
        names="$names $h"
        i=$((i + 1))
    done

    # Wait until every sshd answers with its own host name.
    for h in $names; do
        ok=""
        k=0
        while [ $k -lt 50 ]; do
            if [ "$("$STATE/rsh" "$h" hostname 2>/dev/null)" = "$h" ]; then ok=1; break; fi
            sleep 0.1
            k=$((k + 1))
        done
        [ -n "$ok" ] || die "sshd on $h does not answer (see $STATE/sshd-$h.log)"
    done

    for h in $(echo "$half" | tr ',' ' '); do
        [ -f "$STATE/sshd-$h.pid" ] || die "--half: no host $h"
        cg="$CGROUP_CPU/fc-netns-$h"
        mkdir -p "$cg"
        echo 100000 > "$cg/cpu.cfs_period_us"
        echo 50000 > "$cg/cpu.cfs_quota_us"
        cat "$STATE/sshd-$h.pid" > "$cg/cgroup.procs"
    done

    {
        echo "export PVM_ROOT=/usr/lib/pvm3"
        echo "export PVM_ALLOW_ROOT=1"
        echo "export PVM_RSH=$STATE/rsh"
        echo "export PVM_TMP=$STATE/master-tmp"
        echo "export PVM_NETNS_MASTER=$MASTER_NAME"
        echo "export PVM_NETNS_HOSTS='$(echo $names)'"
    } > "$STATE/env"
    echo "pvm-netns-hosts.sh: hosts$names up; master name $MASTER_NAME; state in $STATE" >&2
}

case "${1:-}" in
    up) shift; up "$@" ;;
    down) down ;;
    env) print_env ;;
    *) echo "usage: $0 up [N] [--half HOST,...] | down | env" >&2; exit 2 ;;
esac
