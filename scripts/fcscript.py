"""What the measurement scripts in scripts/ share: where the checkout's programs are, the
pixels of an image file (read with OpenImageIO), and the exports of a cluster of
network-namespace hosts (scripts/pvm-netns-hosts.sh). A script imports it with its own folder on
sys.path:

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from fcscript import POVRAY_FC, read_pixels
"""
import os
import subprocess
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

TOP = Path(__file__).resolve().parent.parent
BIN = TOP / "build" / "bin"
POVRAY_FC = BIN / "povray-fc"
DEBIAN_POVRAY = Path("/usr/bin/povray")
NETNS = TOP / "scripts" / "pvm-netns-hosts.sh"


def netns_exports(state):
    """What `pvm-netns-hosts.sh env` exports for the cluster of state directory `state`
    (PVM_NETNS_HOSTS, PVM_NETNS_MASTER, PVM_TMP, PVM_RSH, ...), as a dict."""
    out = subprocess.run([str(NETNS), "env"], env=dict(os.environ, PVM_NETNS_STATE=str(state)),
                         capture_output=True, text=True, check=True).stdout
    exports = {}
    for line in out.splitlines():
        key, _, value = line.removeprefix("export ").strip().partition("=")
        if value:
            exports[key] = value.strip("'\"")
    return exports


def read_pixels(path):
    """Pixels of an image file as a uint8 array (height, width, channels), via OpenImageIO."""
    inp = oiio.ImageInput.open(str(path))
    if inp is None:
        raise IOError(f"{path}: {oiio.geterror()}")
    try:
        pixels = inp.read_image(0, 0, 0, inp.spec().nchannels, oiio.UINT8)
    finally:
        inp.close()
    if pixels is None:
        raise IOError(f"{path}: {oiio.geterror()}")
    return np.asarray(pixels)
