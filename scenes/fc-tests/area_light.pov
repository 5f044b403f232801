// fc-test: speedup
// A non-jittered area light; a ball moves and its soft shadow with it.
#version 3.7;
#declare NoDefaultLight = 1;
#include "common.inc"
light_source { <-4, 7, -3> color rgb 1 area_light <2, 0, 0>, <0, 0, 2>, 4, 4 adaptive 1 }
sphere { <-1 + 2 * clock, 0.5, -0.5>, 0.5 pigment { color rgb <0.9, 0.6, 0.3> } }
