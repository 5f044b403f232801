// fc-test:
// Two coincident boxes swap their places in the scene from frame 2 on: the same objects,
// so nothing "changed", but POV-Ray now meets the other one first (with too few objects
// for a bounding tree it tries them in scene order).
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0,1,-4> look_at <0,0.5,0> }
light_source { <3,8,-5> rgb 1 }
#declare Red  = box { <-1,0,0>, <1,1,0.5> pigment { rgb <1,0.2,0.2> } }
#declare Blue = box { <-1,0,0>, <1,1,0.5> pigment { rgb <0.2,0.2,1> } }
#if (frame_number = 1) object { Red } object { Blue } #else object { Blue } object { Red } #end
