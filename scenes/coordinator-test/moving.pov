// coordinator test scene: a sphere moving across a checkered floor, driven only by clock.
// Small and fast; used by tests/test_coordinator*.py. No includes.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0, 2, -6> look_at <0, 0.8, 0> angle 50 }
light_source { <4, 8, -6> color rgb 1 }
light_source { <-6, 5, -3> color rgb 0.4 shadowless }
plane { y, 0 pigment { checker color rgb <0.9, 0.9, 0.85> color rgb <0.2, 0.3, 0.5> scale 0.75 }
        finish { reflection 0.15 } }
sphere { <-2.5 + 5*clock, 0.8 + 0.6*sin(clock*pi), 0.5*cos(clock*2*pi)>, 0.8
         pigment { color rgb <0.9, 0.3, 0.2> } finish { phong 0.8 reflection 0.25 } }
box { <-0.5, 0, 1.5>, <0.5, 1.6, 2.5> rotate y*(30 + 90*clock)
      pigment { color rgb <0.3, 0.8, 0.4> } }
sky_sphere { pigment { gradient y color_map { [0 color rgb <0.7, 0.8, 1>] [1 color rgb <0.2, 0.3, 0.7>] } } }
