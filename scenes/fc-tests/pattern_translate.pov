// fc-test: speedup
// A pigment pattern translated with clock on a static object.
#version 3.7;
#include "common.inc"
sphere { <0, 0.7, 0>, 0.7 pigment { gradient x color_map { [0 color rgb 1] [1 color rgb <0, 0, 1>] } translate x * clock } }
