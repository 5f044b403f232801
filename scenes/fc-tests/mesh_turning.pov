// fc-test: speedup
// A mesh that turns as a whole (a pinwheel of four blades with gaps between them), placed
// by a transformation: every triangle changes, so each is a hull of its own and the rays
// through the gaps of its box to the floor stay clean (povray-fc/README.md, "Meshes").
#version 3.7;
#include "common.inc"
mesh {
  triangle { <0.1, 0, 0>, <0.8, 0.15, 0>, <0.8, -0.15, 0> }
  triangle { <0, 0.1, 0>, <0.15, 0.8, 0>, <-0.15, 0.8, 0> }
  triangle { <-0.1, 0, 0>, <-0.8, 0.15, 0>, <-0.8, -0.15, 0> }
  triangle { <0, -0.1, 0>, <0.15, -0.8, 0>, <-0.15, -0.8, 0> }
  pigment { color rgb <0.9, 0.6, 0.2> }
  rotate z * 20 * clock
  translate <0, 1, 0>
}
