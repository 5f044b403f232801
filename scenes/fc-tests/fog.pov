// fc-test: speedup
// Fog over the scene; a ball moves through it.
#version 3.7;
#include "common.inc"
fog { distance 12 color rgb <0.7, 0.75, 0.8> }
sphere { <-1 + 2 * clock, 0.4, -1>, 0.4 pigment { color rgb <1, 0.4, 0.2> } }
