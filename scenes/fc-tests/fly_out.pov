// fc-test:
// An object flies far out of the scene (and out of the voxel grid).
#version 3.7;
#include "common.inc"
sphere { <0, 0.5 + 40 * clock * clock, 0>, 0.5 pigment { color rgb <1, 1, 0.2> } }
