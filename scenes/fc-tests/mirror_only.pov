// fc-test: speedup
// A ball moves behind the camera, seen only in a mirror.
#version 3.7;
#include "common.inc"
box { <-3, 0, 3.5>, <3, 3, 3.6> pigment { color rgb 0 } finish { reflection 0.9 } }
sphere { <-1 + 2 * clock, 1.2, -8>, 0.6 pigment { color rgb <1, 0.2, 0.2> } }
