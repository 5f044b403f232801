// fc-test:
// Two coincident copies of a shape, one glass and one opaque: a shadow test meets both at
// the same depth. POV-Ray's per-thread shadow cache remembers the opaque one from the last
// pixel and answers "dark" where the search would have met the glass first; so a pixel
// depended on the pixel traced before it. Objects appear in frames 3 and 4.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 6 }
camera { location <0.80, 1.8, -4.5> look_at <0, 0.7, 0.5> angle 55 }
light_source { <1.48, 8, -3.84> color rgb 1 }
plane { y, 0 pigment { checker color rgb 0.8 color rgb 0.3 } }
#declare Ring = difference { torus { 0.206, 0.054 rotate x*90 } object { sphere { 0, 0.459 } translate <-0.081, 0.269, -0.15> } };
#declare Pipe = merge { cylinder { <-0.438, 0, 0>, <0.518, 0, 0>, 0.090 } object { cone { <0, -0.3, 0>, 0.241, <0, 0.3, 0>, 0.086 } translate <0.141, 0.217, -0.15> } }
#declare Shard = mesh {
  triangle { <0.339, 1.321, 1.801>, <0.089, 1.091, -0.124>, <-0.186, 0.488, 0.606> }
  triangle { <0.107, 1.002, 0.176>, <-0.076, 0.548, 1.446>, <0.081, 1.248, 1.435> }
  triangle { <-0.219, 0.364, -0.151>, <0.407, 1.308, 0.216>, <0.277, 0.679, 1.596> }
  triangle { <-0.410, 1.237, 1.941>, <-0.080, 0.847, -0.607>, <-0.225, 0.527, -0.111> }
  translate <0, -0.8, 0>
}
#if (frame_number >= 3) object { Shard pigment { color rgbf <0.07, 0.30, 0.10, 0.8> } interior { ior 1.57 } finish { phong 0.5 } translate <-1.654, 0.286, -0.234> } #end
object { Pipe pigment { color rgbf <0.60, 0.54, 0.46, 0.8> } interior { ior 1.41 } finish { phong 0.5 } translate <1.256, 1.584, -0.557> }
object { Pipe pigment { color rgbf <0.60, 0.54, 0.46, 0.8> } interior { ior 1.41 } finish { phong 0.5 } translate <1.256, 1.584, -0.557> pigment { color rgb <0.63, 0.17, 0.08> } }
object { mesh { triangle { <-0.037, 0.774, 0.740>, <0.197, 0.822, -0.201>, <0.054, 1.253, 1.008> } triangle { <-0.349, 0.911, -0.079>, <-0.391, 0.207, -0.641>, <-0.050, 0.897, 0.616> } triangle { <-0.254, 1.491, 0.066>, <-0.393, 0.679, 1.544>, <0.157, 1.260, 1.966> } translate <0, -0.8, 0> } pigment { color rgbf <0.35, 0.64, 0.32, 0.8> } interior { ior 1.35 } finish { phong clock reflection 0.3 * clock } translate <1.780, 0.629, 1.948> }
object { Ring pigment { color rgbf <0.26, 0.36, 0.32, 0.8> } interior { ior 1.50 } finish { phong 0.5 } translate <0.808, 1.154, -0.337> }
#if (frame_number >= 4) object { mesh { triangle { <0.119, 0.641, 0.404>, <-0.421, 1.169, -0.536>, <-0.144, 0.868, 0.262> } triangle { <0.176, 0.494, 0.421>, <0.301, 0.552, -0.601>, <0.368, 0.423, 1.594> } triangle { <0.086, 0.981, 0.860>, <0.423, 0.736, 0.103>, <0.326, 1.161, 0.540> } triangle { <0.258, 0.760, -0.355>, <0.221, 1.115, 1.805>, <-0.324, 1.477, 1.881> } translate <0, -0.8, 0> } pigment { color rgb <0.65, 0.36, 0.95> } finish { phong 0.00 } translate <1.442, 1.015, -0.202> } #end
