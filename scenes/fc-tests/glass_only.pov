// fc-test: speedup
// A ball moves where it is seen only through a glass slab.
#version 3.7;
#include "common.inc"
box { <-1.5, 0, 0>, <1.5, 2, 0.3> pigment { color rgbf <1, 1, 1, 0.95> } interior { ior 1.5 } }
sphere { <-0.8 + 1.6 * clock, 0.9, 1.2>, 0.35 pigment { color rgb <1, 0.3, 0.1> } }
