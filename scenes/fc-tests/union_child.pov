// fc-test: speedup
// One child of a union moves; the union's other children (a wide wall and a post) stay:
// only the moving child's old and new places are dirty, not the union's whole box.
#version 3.7;
#include "common.inc"
union {
  box { <-2.5, 0, 2>, <2.5, 2, 2.2> }
  cylinder { <-2, 0, 0>, <-2, 1.8, 0>, 0.1 }
  sphere { <-0.5 + clock, 0.5, -0.5>, 0.3 }
  pigment { color rgb <0.8, 0.4, 0.3> }
  translate <0, 0, 0.5>
}
