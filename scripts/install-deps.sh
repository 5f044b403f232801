#!/bin/sh
# Installs every Debian package povray-fc needs to build, test and demo. Idempotent.
# When everything is installed already it only checks, so `make` can call it each time.
set -eu

# What we use ourselves (POV-Ray's build dependencies come from `apt-get build-dep`).
PACKAGES="dpkg-dev quilt ccache autoconf-archive build-essential
    pvm pvm-dev
    libopenimageio-dev openimageio-tools python3-openimageio
    python3-pytest python3-numpy python3-matplotlib
    cmake libgtest-dev
    povray povray-examples
    openssh-server openssh-client iproute2 procps psmisc strace linux-perf"
# A few of POV-Ray's build dependencies, enough to tell whether build-dep has run.
BUILD_DEP_MARKERS="libboost-thread-dev libopenexr-dev libsdl1.2-compat-dev libtiff-dev libxpm-dev"

src_list=/etc/apt/sources.list.d/povray-fc-deb-src.sources

have_deb_src() {
    grep -rqs '^Types:.*deb-src' /etc/apt/sources.list.d/ || grep -qs '^deb-src ' /etc/apt/sources.list
}

all_installed() {
    for p in $PACKAGES $BUILD_DEP_MARKERS; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || return 1
    done
}

if have_deb_src && all_installed; then
    exit 0
fi

[ "$(id -u)" = 0 ] || {
    echo "install-deps.sh: packages are missing and installing them needs root: run 'sudo make deps'" >&2
    exit 1
}

# apt-get source/build-dep need a deb-src entry mirroring the bookworm deb one.
if ! have_deb_src; then
    cat > "$src_list" <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
fi

export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get build-dep -y -q povray
# shellcheck disable=SC2086 # word splitting of the package lists is intended
apt-get install -y -q --no-install-recommends $PACKAGES $BUILD_DEP_MARKERS
