// fc-test: speedup +A0.1 +AM2 +R2 +J
// Adaptive anti-aliasing with jitter and a moving ball.
#version 3.7;
#include "common.inc"
sphere { <-1 + 2 * clock, 0.4, -1>, 0.4 pigment { color rgb <0.2, 1, 0.6> } }
