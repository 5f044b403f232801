// A glass ball bounces around a brick room: the sample animation of Davis & Davis's
// Figure 1 (reconstructed). The ball is thrown from the back left of the room, bounces
// on the floor and off the right wall and the back wall, and loses some energy at
// every bounce.
//
// Motion (clock 0 .. 1 is Duration seconds; scene units are metres):
// - Flight between bounces is exact free fall: p(t) = p0 + v0 t - g t^2 / 2 (y up),
//   no air drag.
// - The floor and the four walls are planes (for the motion); the ball (radius Rb) bounces when its
//   surface touches one. The time of the next contact is solved exactly (a quadratic
//   for the floor, linear for a wall), the flight is advanced to it, and the normal
//   velocity component is reflected and scaled by the coefficient of restitution
//   (floor 0.8, walls 0.9); the tangential components are kept (no friction, no spin).
//   Event by event until the frame's time, so there is no time step and no error
//   beyond floating point.
// - When a floor bounce leaves less than 5 cm/s upwards the ball stays on the floor
//   (rolling without friction) instead of bouncing infinitely often.
// Declare BounceDebug=1 prints the ball's state per frame.
#version 3.7;

global_settings { assumed_gamma 1.0 max_trace_level 8 }

// ---------------------------------------------------------------- the room
#declare RoomX0 = -4;  #declare RoomX1 = 4;     // side walls
#declare RoomZ0 = -7;  #declare RoomZ1 = 4;     // front wall (behind the camera), back wall
#declare RoomY1 = 5;                            // ceiling

// ---------------------------------------------------------------- the throw
#declare Rb       = 0.75;                // ball radius
#declare Gravity  = 9.81;
#declare EFloor   = 0.80;                // coefficients of restitution
#declare EWall    = 0.90;
#declare Duration = 3.5;                 // seconds over clock 0 .. 1
#declare P0 = <-2.2, 2.8, 1.2>;          // position at clock 0, m
#declare V0 = < 3.4, 1.6, 1.4>;          // velocity at clock 0, m/s

#declare Target = clock * Duration;
#declare P = P0;
#declare V = V0;
#declare T = 0;
#declare OnFloor = false;
#declare Bounces = 0;
#declare Big = 1e9;
#while (T < Target & Bounces < 1000)
  // Time to each contact from the current state (Big: none ahead).
  #if (OnFloor)
    #declare Tf = Big;
  #else
    #declare Tf = (V.y + sqrt(max(0, V.y * V.y + 2 * Gravity * (P.y - Rb)))) / Gravity;
  #end
  #declare Tx = Big;
  #if (V.x > 0) #declare Tx = (RoomX1 - Rb - P.x) / V.x; #end
  #if (V.x < 0) #declare Tx = (RoomX0 + Rb - P.x) / V.x; #end
  #declare Tz = Big;
  #if (V.z > 0) #declare Tz = (RoomZ1 - Rb - P.z) / V.z; #end
  #if (V.z < 0) #declare Tz = (RoomZ0 + Rb - P.z) / V.z; #end
  #declare Dt = max(0, min(Tf, Tx, Tz));
  #declare Hit = (T + Dt < Target);
  #if (!Hit) #declare Dt = Target - T; #end
  // Advance the flight (or the roll) by Dt.
  #if (OnFloor)
    #declare P = P + V * Dt;
  #else
    #declare P = P + V * Dt - <0, Gravity * Dt * Dt / 2, 0>;
    #declare V = V - <0, Gravity * Dt, 0>;
  #end
  #declare T = T + Dt;
  #if (Hit)
    #declare Bounces = Bounces + 1;
    #if (Dt = Tf)
      #declare P = <P.x, Rb, P.z>;
      #declare V = <V.x, -EFloor * V.y, V.z>;
      #if (V.y < 0.05)
        #declare OnFloor = true;
        #declare V = <V.x, 0, V.z>;
      #end
    #end
    #if (Dt = Tx)
      #declare P = <(V.x > 0 ? RoomX1 - Rb : RoomX0 + Rb), P.y, P.z>;
      #declare V = <-EWall * V.x, V.y, V.z>;
    #end
    #if (Dt = Tz)
      #declare P = <P.x, P.y, (V.z > 0 ? RoomZ1 - Rb : RoomZ0 + Rb)>;
      #declare V = <V.x, V.y, -EWall * V.z>;
    #end
  #end
#end

#ifdef (BounceDebug)
  #debug concat("Bounce: clock ", str(clock, 0, 5), " t ", str(T, 0, 4), " s, ", str(Bounces, 0, 0), " bounces\n")
  #debug concat("Bounce: p <", vstr(3, P, ", ", 0, 4), ">  v <", vstr(3, V, ", ", 0, 4), ">\n")
#end

// ---------------------------------------------------------------- look
camera {
  location <-0.6, 2.3, -6.5>
  look_at  <0.4, 1.3, 0>
  angle 72
}

light_source { <-1.5, 4.6, -3.5> color rgb 1.0 }
light_source { <2.5, 4.2, 1.0> color rgb 0.35 shadowless }

#declare BrickDepth = 0.36;
#declare Bricks = pigment {
  brick color rgb <0.70, 0.68, 0.62> color rgb <0.50, 0.16, 0.08>
  brick_size <0.66, 0.24, BrickDepth> mortar 0.05
}
// Bricks on a surface whose normal is the pattern's z axis, at Offset along it: the
// surface cuts the middle of a course of bricks, never the mortar between courses.
#macro SurfaceBricks(Offset) pigment { Bricks translate z * (Offset - BrickDepth / 2) } #end
#declare BrickFinish = finish { ambient 0.05 diffuse 0.75 }

// The room: floor, four walls and ceiling are slabs 0.2 m thick (boxes, not planes, so
// the room is bounded and frame coherence's voxel grid spans all of it).
#declare Slab = 0.2;
// Floor: bricks laid flat.
box { <RoomX0 - Slab, -Slab, RoomZ0 - Slab>, <RoomX1 + Slab, 0, RoomZ1 + Slab>
  texture { SurfaceBricks(0) rotate x * 90 finish { BrickFinish } }
}
// The four walls (the side walls' pattern rotated about y so the courses run along them).
box { <RoomX0 - Slab, 0, RoomZ1>, <RoomX1 + Slab, RoomY1, RoomZ1 + Slab> texture { SurfaceBricks(RoomZ1) finish { BrickFinish } } }
box { <RoomX0 - Slab, 0, RoomZ0 - Slab>, <RoomX1 + Slab, RoomY1, RoomZ0> texture { SurfaceBricks(RoomZ0) finish { BrickFinish } } }
box { <RoomX0 - Slab, 0, RoomZ0>, <RoomX0, RoomY1, RoomZ1> texture { SurfaceBricks(RoomX0) rotate y * 90 finish { BrickFinish } } }
box { <RoomX1, 0, RoomZ0>, <RoomX1 + Slab, RoomY1, RoomZ1> texture { SurfaceBricks(RoomX1) rotate y * 90 finish { BrickFinish } } }
// Ceiling.
box { <RoomX0 - Slab, RoomY1, RoomZ0 - Slab>, <RoomX1 + Slab, RoomY1 + Slab, RoomZ1 + Slab>
  pigment { color rgb 0.85 } finish { ambient 0.1 diffuse 0.6 }
}

// The glass ball.
sphere { P, Rb
  pigment { color rgbf <0.97, 1.0, 0.98, 0.94> }
  finish { ambient 0 diffuse 0.05 specular 0.9 roughness 0.002 reflection { 0.04, 0.5 fresnel } conserve_energy }
  interior { ior 1.5 }
}
