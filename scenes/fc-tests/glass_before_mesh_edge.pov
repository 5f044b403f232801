// fc-test: +W160 +H120
// A filtering cylinder stretches between the floor and a mesh that shadows it. A shadow
// test from the floor passes the cylinder, and POV-Ray's shadow loop goes on from where it
// left it: whether the ray from there meets the mesh near a triangle's edge hangs on that
// point in floating point, so a few pixels at the edge of the mesh's shadow flip between
// dark and tinted as the cylinder changes, though the mesh stays. (Found by
// scripts/fc-random-scenes; a few pixels at this size.)
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 6 }
camera { location <0.93, 1.8, -4.5> look_at <0, 0.7, 0.5> angle 55 }
plane { y, 0 pigment { checker color rgb 0.8 color rgb 0.3 } }
light_source { <-4.24, 5, 4> color rgb 0.5 }
mesh {
  triangle { <0.274, 0.757, 1.343>, <0.350, 0.807, 1.189>, <0.317, 0.266, 1.075> }
  triangle { <0.388, 1.127, 1.489>, <-0.479, 0.288, 0.517>, <0.376, 1.215, 0.067> }
  triangle { <0.126, 1.084, 1.804>, <0.359, 0.731, 1.715>, <0.494, 1.592, -0.661> }
  triangle { <-0.192, 0.954, -0.841>, <0.431, 1.090, -0.473>, <0.292, 1.181, 0.708> }
  translate <-1.355, 0.578, 0.861>
  pigment { color rgb <0.26, 0.93, 0.06> }
}
cylinder {
  <-0.371, 0, 0>, <0.391, 0, 0>, 0.140
  translate <-0.170, 0.135, -0.15>
  scale <1 + 0.6 * clock, 1, 1 - 0.3 * clock>
  pigment { color rgbf <0.85, 0.40, 0.90, 0.7> }
  translate <-0.843, 1.341, 0.326>
}
