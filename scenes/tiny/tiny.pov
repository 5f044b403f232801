// A tiny animated scene: so cheap to trace that per-frame overhead dominates.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 1, -4> look_at <0, 0.5, 0> }
light_source { <3, 5, -4> color rgb 1 }
plane { y, 0 pigment { checker color rgb 0.8 color rgb 0.2 } }
sphere { <-1 + 2 * clock, 0.5, 0>, 0.5 pigment { color rgb <0.9, 0.3, 0.2> } }
