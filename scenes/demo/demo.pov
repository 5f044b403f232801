// povray-fc demo: a chrome ball rolls across a checkered floor past a glass
// sphere and a static column. Most of the picture does not change between
// frames, which is the case frame coherence is made for.
#version 3.7;

global_settings { assumed_gamma 1.0 max_trace_level 5 }

camera {
  location <0, 3.2, -7.5>
  look_at  <0, 0.8, 0>
  angle 50
}

light_source { <-6, 9, -5> color rgb 1.0 }
light_source { <5, 6, -8> color rgb 0.35 shadowless }

sky_sphere {
  pigment { gradient y color_map { [0 color rgb <0.75, 0.85, 1.0>] [1 color rgb <0.2, 0.35, 0.8>] } }
}

plane {
  y, 0
  pigment { checker color rgb 0.9 color rgb 0.15 scale 1.0 }
  finish { diffuse 0.8 reflection 0.12 }
}

// Static glass sphere: its refraction shows the moving ball only in some frames.
sphere {
  <1.6, 0.9, 1.2>, 0.9
  pigment { color rgbf <0.95, 1.0, 0.95, 0.9> }
  finish { specular 0.6 roughness 0.005 reflection 0.05 }
  interior { ior 1.5 }
}

// Static column.
cylinder {
  <-2.4, 0, 2.0>, <-2.4, 2.6, 2.0>, 0.35
  pigment { color rgb <0.8, 0.35, 0.2> }
  finish { diffuse 0.7 specular 0.3 }
}

// The moving chrome ball: rolls from left to right, bouncing slightly.
#declare BallX = -3.0 + 6.0 * clock;
#declare BallY = 0.5 + 0.6 * abs(sin(clock * 2 * pi));
sphere {
  <BallX, BallY, -0.6>, 0.5
  pigment { color rgb 0.05 }
  finish { reflection 0.8 specular 0.9 roughness 0.002 diffuse 0.2 }
}
