// fc-test: speedup +A0.1 +AM1
// Anti-aliasing method 1 (depends on the block partition) with a moving ball.
#version 3.7;
#include "common.inc"
sphere { <-1 + 2 * clock, 0.4, -1>, 0.4 pigment { color rgb <1, 0.2, 0.6> } }
