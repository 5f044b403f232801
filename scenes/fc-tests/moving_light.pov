// fc-test:
// The light moves: every pixel may change.
#version 3.7;
#declare NoDefaultLight = 1;
#include "common.inc"
light_source { <-5 + 10 * clock, 8, -4> color rgb 1 }
sphere { <0, 0.7, 0>, 0.7 pigment { color rgb 0.9 } }
