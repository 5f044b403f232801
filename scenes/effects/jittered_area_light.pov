// A jittered area light: sample positions on the light drawn at random.
#version 3.7;
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 area_light <1.5, 0, 0>, <0, 0, 1.5>, 5, 5 jitter adaptive 1 }
sphere { <0, 0.6, 0>, 0.6 pigment { color rgb <0.9, 0.7, 0.2> } }
