// Media method 3 with jitter: jittered sample positions along each ray.
#version 3.7;
#include "common.inc"
light_source { <-3, 5, -3> color rgb 1 }
box { <-0.8, 0, -0.8>, <0.8, 1.4, 0.8> pigment { rgbt 1 } hollow
  interior { media { method 3 jitter 0.5 intervals 1 samples 4 scattering { 1, rgb 0.6 } } } }
