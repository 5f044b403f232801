// fc-test: speedup
// Focal blur (many camera rays per pixel) with a moving ball.
#version 3.7;
#declare NoDefaultCamera = 1;
#include "common.inc"
camera { location <0, 2.5, -6> look_at <0, 0.8, 0> angle 55 aperture 0.3 blur_samples 8 focal_point <0, 0.5, 0> }
sphere { <-1 + 2 * clock, 0.4, -1>, 0.4 pigment { color rgb <0.6, 0.2, 1> } }
