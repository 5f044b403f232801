// fc-test: speedup
// An object outside the camera's view casts a moving shadow onto the floor.
#version 3.7;
#declare NoDefaultLight = 1;
#include "common.inc"
light_source { <0, 20, 0> color rgb 1 }
sphere { <-1 + 2 * clock, 10, 0>, 0.8 pigment { color rgb 1 } }
