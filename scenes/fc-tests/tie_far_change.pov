// fc-test: +KF0.6
// Three pairs of coincident boxes (each pair: one red, one blue, same corners). POV-Ray
// shows the box its bounding tree meets first; a small sphere far away moves, the tree is
// rebuilt in another shape, and a pair may show its other box though nothing near it moved.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0,3,-6> look_at <0,0.6,0> angle 50 }
light_source { <3,8,-5> rgb 1 }
#for (I, 0, 2)
  box { <-2.2 + I*1.2,0,0>, <-1.4 + I*1.2,1.2,0.4> pigment { rgb <1,0.2,0.2> } }
  box { <-2.2 + I*1.2,0,0>, <-1.4 + I*1.2,1.2,0.4> pigment { rgb <0.2,0.2,1> } }
#end
#for (I, 0, 3) sphere { <-3 + I*0.65, 0.15, 2>, 0.15 pigment { rgb <0.5,1,0.5> } } #end
sphere { <-6 + 12*clock, 0.2, -3>, 0.2 pigment { rgb 1 } }
