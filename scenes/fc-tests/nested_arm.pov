// fc-test: speedup
// An arm modelled the usual way: declared parts placed with object { }, nested unions
// for the joints, the whole arm rotated at the shoulder. Only the wrist turns: only the
// hand's old and new places change, not the arm's or the robot's.
#version 3.7;
#include "common.inc"
#declare Finger = cylinder { <0, 0, 0>, <0.35, 0, 0>, 0.05 }
#declare Hand = union {
  sphere { <0, 0, 0>, 0.14 }
  object { Finger rotate <0, 0, 25> }
  object { Finger }
  object { Finger rotate <0, 0, -25> }
  pigment { color rgb <0.9, 0.6, 0.3> }
}
#declare Forearm = union {
  cylinder { <0, 0, 0>, <1.1, 0, 0>, 0.09 }
  object { Hand rotate <0, 0, -40 + 80 * clock> translate <1.1, 0, 0> }
}
#declare Arm = union {
  sphere { <0, 0, 0>, 0.15 }
  cylinder { <0, 0, 0>, <1.0, 0, 0>, 0.11 }
  object { Forearm rotate <0, 0, 35> translate <1.0, 0, 0> }
  pigment { color rgb <0.6, 0.65, 0.7> }
  finish { phong 0.5 }
}
union {
  box { <-0.4, 0, -0.4>, <0.4, 1.2, 0.4> pigment { color rgb <0.3, 0.3, 0.35> } }
  object { Arm rotate <0, 0, 10> translate <0, 1.25, 0> }
  translate <-1.2, 0, 0>
}
