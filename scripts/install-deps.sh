#!/bin/sh
# Installs every Debian package povray-fc needs to build, test and demo. Idempotent; run as root.
set -eu

[ "$(id -u)" = 0 ] || { echo "install-deps.sh: must run as root (apt-get)" >&2; exit 1; }

# apt-get source/build-dep need a deb-src entry mirroring the bookworm deb one.
src_list=/etc/apt/sources.list.d/povray-fc-deb-src.sources
if ! grep -rqs '^Types:.*deb-src' /etc/apt/sources.list.d/ && \
   ! grep -qs '^deb-src ' /etc/apt/sources.list; then
    cat > "$src_list" <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm bookworm-updates
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
    rm -f /var/lib/apt/lists/povray-fc-updated
fi

export DEBIAN_FRONTEND=noninteractive
# Refresh package lists at most once per day; a stale list makes apt-get source miss.
stamp=/var/lib/apt/lists/povray-fc-updated
if [ ! -e "$stamp" ] || [ -n "$(find "$stamp" -mmin +1440)" ] || [ "$src_list" -nt "$stamp" ]; then
    apt-get update -q
    touch "$stamp"
fi

apt-get build-dep -y -q povray
apt-get install -y -q --no-install-recommends \
    dpkg-dev quilt ccache autoconf-archive \
    pvm pvm-dev \
    libopenimageio-dev openimageio-tools python3-openimageio \
    python3-pytest python3-numpy python3-matplotlib \
    cmake libgtest-dev \
    povray povray-examples \
    openssh-server openssh-client iproute2 procps psmisc \
    linux-perf
