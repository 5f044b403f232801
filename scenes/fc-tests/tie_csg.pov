// fc-test: +KF0.6
// Coincident CSG objects: pairs of identical differences (a box with a ball cut out), one
// red and one blue. Which one POV-Ray shows is decided by its bounding tree, which a small
// sphere moving far away reshapes.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera { location <0,3,-6> look_at <0,0.6,0> angle 50 }
light_source { <3,8,-5> rgb 1 }
#macro Cut(X, Colour)
  difference {
    box { <X,0,0>, <X+0.8,1.2,0.4> }
    sphere { <X+0.4,1.2,0>, 0.35 }
    pigment { rgb Colour }
  }
#end
#for (I, 0, 2)
  Cut(-2.2 + I*1.2, <1,0.2,0.2>)
  Cut(-2.2 + I*1.2, <0.2,0.2,1>)
#end
#for (I, 0, 3) sphere { <-3 + I*0.65, 0.15, 2>, 0.15 pigment { rgb <0.5,1,0.5> } } #end
sphere { <-6 + 12*clock, 0.2, -3>, 0.2 pigment { rgb 1 } }
