// fc-test: speedup
// Meshes kept as written (no transformation) some of whose vertices move: each is tested at
// the triangles that changed and at the rims of those it kept, not in its whole box
// (povray-fc/README.md, "Meshes"). A strip on a grid (edges along the axes, shared
// vertices) whose far corner rises, with a small triangle far to its side so that the
// mesh's box spans the view; smooth triangles whose shared vertex moves, casting shadows;
// a translated mesh whose box grows (tested in its box); and a turned one whose box stays.
#version 3.7;
#include "common.inc"
mesh {
  triangle { <-1.8, 0.3, 0>, <-1.4, 0.3, 0>, <-1.8, 0.7, 0> }
  triangle { <-1.4, 0.3, 0>, <-1.4, 0.7, 0>, <-1.8, 0.7, 0> }
  triangle { <-1.4, 0.3, 0>, <-1.0, 0.3, 0>, <-1.4, 0.7, 0> }
  triangle { <-1.0, 0.3, 0>, <-1.0, 0.7 + 0.4 * clock, 0>, <-1.4, 0.7, 0> }
  triangle { <1.4, 1.6, 0.5>, <1.7, 1.6, 0.5>, <1.55, 1.9, 0.5> }
  pigment { color rgb <0.9, 0.5, 0.2> }
}
#declare Apex = <0, 0.9 + 0.3 * clock, -0.6 + 0.2 * clock>;
mesh {
  smooth_triangle { <-0.5, 0.2, -0.4>, <-0.3, 0.2, -1>, <0.5, 0.2, -0.4>, <0.3, 0.2, -1>, Apex, <0, 0.4, -1> }
  smooth_triangle { <0.5, 0.2, -0.4>, <0.3, 0.2, -1>, <0.6, 0.9, 0.2>, <0.5, 0, -1>, Apex, <0, 0.4, -1> }
  pigment { color rgb <0.3, 0.8, 0.5> }
  finish { phong 0.6 }
}
mesh {
  triangle { <0, 0, 0>, <0.4, 0, 0>, <0.2, 0.3 + 0.2 * clock, 0> }
  triangle { <0.5, 0, 0.2>, <0.8, 0, 0.2>, <0.65, 0.3, 0.2> }
  pigment { color rgb <0.8, 0.3, 0.7> }
  translate <0.8, 0.9, -0.3>
}
// A fan around a centre vertex that slides inside its square, turned and moved into place:
// its box stays, so its triangles are kept.
#declare Centre = <0.1 * clock, 0.05 * clock, 0>;
mesh {
  triangle { <-0.3, -0.3, 0>, <0.3, -0.3, 0>, Centre }
  triangle { <0.3, -0.3, 0>, <0.3, 0.3, 0>, Centre }
  triangle { <0.3, 0.3, 0>, <-0.3, 0.3, 0>, Centre }
  triangle { <-0.3, 0.3, 0>, <-0.3, -0.3, 0>, Centre }
  pigment { color rgb <0.2, 0.4, 0.9> }
  rotate <0, 30, 10> translate <1.2, 0.7, -1>
}
