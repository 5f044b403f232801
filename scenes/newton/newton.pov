// Newton's cradle: the "Newton" animation of Davis & Davis, section 4 (designed there
// by Chris Gulka; this is a reconstruction). Five chrome marbles hang by two strings
// each from a frame; the marble on the left end is raised and released, swings down,
// hits the row, and the momentum passes through the three resting marbles to the
// marble on the right end, which swings out and back, hits the row, and sends the
// left one out again.
//
// Objects, as the paper counts them: one plane, five spheres, sixteen cylinders
// (two strings per marble = 10, and the frame: four posts and two top bars = 6).
// Two lights.
//
// Motion (clock 0 .. 1 is exactly one period of the cradle, left marble raised at
// clock 0 and again at clock 1):
// - The cradle is taken as ideal: collisions are elastic and instantaneous, and the
//   marbles touch at rest, so each collision passes the whole momentum of the
//   incoming end marble through the row to the other end marble (equal masses), and
//   the middle three never move. Energy is conserved.
// - Then at every instant at most one end marble is off its rest position, and its
//   angle is that of one free pendulum released from -Theta0: while the free
//   pendulum's angle is negative the left marble swings, while it is positive the
//   right marble swings (the free pendulum passing the bottom is the collision).
// - The free pendulum is exact, not small-angle: theta'' = -(g/L) sin(theta) has the
//   closed-form solution sin(theta/2) = -k sn(K + t sqrt(g/L) | k), k = sin(Theta0/2),
//   with Jacobi's elliptic sn and K = K(k); its period is T = 4 sqrt(L/g) K(k). Both
//   come from one arithmetic-geometric mean (Abramowitz and Stegun 17.6 and 16.4),
//   four or five steps to double precision. (Until 2026-12-04 (7b69f56) the angle
//   was integrated with up to 400 Runge-Kutta steps a frame, error about 1e-8 rad:
//   half of every frame's set-up time went to that loop in the parser, a cost the
//   paper's scene did not have and that every slave of frame division paid again.)
//
// Optional declarations (INI "Declare=Name=value" or command line "Declare=Name=value"):
//   Theta0Deg  release angle in degrees (default 35)
//   Periods    cradle periods over clock 0 .. 1 (default 1)
//   NewtonDebug=1 prints the marble angles per frame.
#version 3.7;

global_settings { assumed_gamma 1.0 max_trace_level 5 }

// ---------------------------------------------------------------- dimensions
// Scene units are centimetres.
#declare R      = 1.0;       // marble radius
#declare L      = 6.5;       // pivot line to marble centre
#declare H      = 9.5;       // height of the pivot lines (top bars) above the floor
#declare D      = 2.6;       // the two strings of a marble hang from z = -D and z = +D
#declare FrameX = 9.5;       // posts at x = -FrameX and +FrameX
#declare PostR  = 0.16;
#declare BarR   = 0.20;
#declare StringR = 0.03;

#ifndef (Theta0Deg) #declare Theta0Deg = 35; #end
#ifndef (Periods)   #declare Periods = 1; #end

// ---------------------------------------------------------------- pendulum
#declare Gravity = 981;                       // cm/s^2
#declare Omega   = sqrt(Gravity / L);         // small-angle angular frequency, 1/s
#declare Theta0  = radians(Theta0Deg);

// The arithmetic-geometric mean of 1 and cos(Theta0/2): AgmA[n] and AgmC[n] are
// a_n and c_n of Abramowitz and Stegun 17.6 (b_n is needed only for the next step).
#declare AgmK  = sin(Theta0 / 2);             // the modulus k
#declare AgmA  = array[16]
#declare AgmC  = array[16]
#declare AgmA[0] = 1;
#declare AgmC[0] = AgmK;
#declare AgmB  = cos(Theta0 / 2);
#declare AgmN  = 0;
#while (abs(AgmC[AgmN]) > 1e-16 & AgmN < 15)
  #declare AgmA[AgmN + 1] = (AgmA[AgmN] + AgmB) / 2;
  #declare AgmC[AgmN + 1] = (AgmA[AgmN] - AgmB) / 2;
  #declare AgmB = sqrt(AgmA[AgmN] * AgmB);
  #declare AgmN = AgmN + 1;
#end
#declare EllipticK = pi / (2 * AgmA[AgmN]);    // K(k), a quarter period of sn
#declare Period = 4 * EllipticK / Omega;       // seconds

// Time since release, reduced to one period (the motion repeats exactly).
#declare Time = mod(clock * Periods * Period, Period);
#if (Time < 0) #declare Time = Time + Period; #end

// sn and cn of u = K + Omega t by the descending Landen transformation
// (Abramowitz and Stegun 16.4): phi_N = 2^N a_N u, phi_(n-1) = (phi_n +
// asin(c_n / a_n sin(phi_n))) / 2, sn = sin(phi_0), cn = cos(phi_0).
#declare Phi = pow(2, AgmN) * AgmA[AgmN] * (EllipticK + Omega * Time);
#declare I = AgmN;
#while (I > 0)
  #declare Phi = (Phi + asin(AgmC[I] / AgmA[I] * sin(Phi))) / 2;
  #declare I = I - 1;
#end
#declare Th = -2 * asin(AgmK * sin(Phi));     // the free pendulum's angle
#declare Om = -2 * AgmK * Omega * cos(Phi);   // and its angular velocity, theta'

// Angles of the five marbles (positive swings towards +x). Only the end marbles move.
#declare Angle = array[5] { 0, 0, 0, 0, 0 }
#if (Th < 0)
  #declare Angle[0] = Th;
#else
  #declare Angle[4] = Th;
#end

#ifdef (NewtonDebug)
  #debug concat("Newton: clock ", str(clock, 0, 5), " t ", str(Time, 0, 5), " s of ", str(Period, 0, 5), " s\n")
  #debug concat("Newton: left ", str(degrees(Angle[0]), 0, 3), " deg, right ", str(degrees(Angle[4]), 0, 3), " deg\n")
  #debug concat("Newton: energy ", str(Om * Om / 2 + Omega * Omega * (1 - cos(Th)), 0, 8),
                " (at release ", str(Omega * Omega * (1 - cos(Theta0)), 0, 8), ")\n")
#end

// ---------------------------------------------------------------- look
camera {
  location <-6.0, 8.0, -20.0>
  look_at  <0.3, 5.0, 0>
  angle 56
}

light_source { <-18, 30, -22> color rgb 1.0 }
light_source { <20, 14, -16> color rgb 0.3 shadowless }

sky_sphere {
  pigment {
    gradient y
    color_map { [0 color rgb <0.60, 0.62, 0.66>] [0.35 color rgb <0.22, 0.27, 0.40>] [1 color rgb <0.05, 0.07, 0.15>] }
  }
}

#declare Chrome = texture {
  pigment { color rgb <0.75, 0.76, 0.78> }
  finish { ambient 0 diffuse 0.08 reflection { 0.8 metallic } specular 0.9 roughness 0.001 brilliance 4 }
}
#declare Brass = texture {
  pigment { color rgb <0.55, 0.40, 0.16> }
  finish { ambient 0 diffuse 0.45 reflection { 0.25 metallic } specular 0.6 roughness 0.01 }
}
#declare StringTex = texture {
  pigment { color rgb 0.85 }
  finish { ambient 0.1 diffuse 0.8 }
}

// The floor.
plane {
  y, 0
  pigment { checker color rgb <0.62, 0.56, 0.46> color rgb <0.12, 0.10, 0.09> scale 3 }
  finish { ambient 0 diffuse 0.75 reflection 0.12 }
}

// The frame: four posts and the two top bars that carry the strings.
#declare Z = -1;
#while (Z <= 1)
  cylinder { <-FrameX, 0, Z * D>, <-FrameX, H, Z * D>, PostR texture { Brass } }
  cylinder { < FrameX, 0, Z * D>, < FrameX, H, Z * D>, PostR texture { Brass } }
  cylinder { <-FrameX, H, Z * D>, < FrameX, H, Z * D>, BarR texture { Brass } }
  #declare Z = Z + 2;
#end

// The marbles, touching at rest, and their strings (pivot line at x = rest x, y = H).
#declare I = 0;
#while (I < 5)
  #declare RestX = (I - 2) * 2 * R;
  #declare Centre = <RestX + L * sin(Angle[I]), H - L * cos(Angle[I]), 0>;
  sphere { Centre, R texture { Chrome } }
  cylinder { <RestX, H, -D>, Centre, StringR texture { StringTex } }
  cylinder { <RestX, H,  D>, Centre, StringR texture { StringTex } }
  #declare I = I + 1;
#end
