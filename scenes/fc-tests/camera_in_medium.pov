// fc-test:
// The camera stands inside a box of fog (media) whose density changes: every camera ray
// starts in it, whatever it ends on. The box is around the camera, so fc renders full
// frames.
#version 3.7;
#declare NoDefaultCamera = 1;
#include "common.inc"
camera { location <0, 1.5, -3> look_at <0, 0.8, 0> angle 55 }
box { <-5, -0.1, -5>, <5, 5, 5>
  hollow
  pigment { color rgbf 1 }
  interior { media { absorption 0.05 + 0.2 * clock method 3 } }
}
sphere { <0, 0.6, 0.5>, 0.5 pigment { color rgb <0.9, 0.5, 0.2> } }
