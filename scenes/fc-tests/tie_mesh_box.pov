// fc-test: +KF0.6
// A mesh whose triangles lie exactly in the front faces of boxes: each box face and its
// two triangles tie in depth, and the bounding tree, which a small sphere moving far away
// reshapes, decides whether the red box or the blue mesh shows.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0,3,-6> look_at <0,0.6,0> angle 50 }
light_source { <3,8,-5> rgb 1 }
#for (I, 0, 2)
  #declare X = -2.2 + I*1.2;
  box { <X,0,0>, <X+0.8,1.2,0.4> pigment { rgb <1,0.2,0.2> } }
  mesh {
    triangle { <X,0,0>, <X+0.8,0,0>, <X+0.8,1.2,0> }
    triangle { <X,0,0>, <X+0.8,1.2,0>, <X,1.2,0> }
    pigment { rgb <0.2,0.2,1> }
  }
#end
#for (I, 0, 3) sphere { <-3 + I*0.65, 0.15, 2>, 0.15 pigment { rgb <0.5,1,0.5> } } #end
sphere { <-6 + 12*clock, 0.2, -3>, 0.2 pigment { rgb 1 } }
