"""What the measurement scripts in scripts/ share: where the checkout's programs are, and the
pixels of an image file (read with OpenImageIO). A script imports it with its own folder on
sys.path:

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from fcscript import POVRAY_FC, read_pixels
"""
from pathlib import Path

import numpy as np
import OpenImageIO as oiio

TOP = Path(__file__).resolve().parent.parent
BIN = TOP / "build" / "bin"
POVRAY_FC = BIN / "povray-fc"
DEBIAN_POVRAY = Path("/usr/bin/povray")


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
