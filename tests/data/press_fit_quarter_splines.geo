// prm/meshes/press_fit_quarter.geo with its three circles written as
// splines through points of them (tests/press_fit_splines): the shaft's
// surface (radius b) and the hub's bore (radius b - delta) as Splines
// (gmsh's Catmull-Rom spline, through its points), the hub's outer
// circle (radius c) as a BSpline (a uniform cubic B-spline of its control
// points, which gmsh makes pass through the first and the last). Each has
// n + 1 points at the angles pi/2 i/n: n = 4096 for the contact splines
// (their deviation from the circle, largest in the end pieces, falls as
// n^-2: 1.1e-4 mm with n = 128, a tenth of delta, too much for P1's gap
// on refined meshes; 1.1e-7 mm with 4096), n = 128 for the B-spline. The B-spline passes at
// (P_{i-1} + 4 P_i + P_{i+1}) / 6 = (4 + 2 cos(pi / (2 n))) / 6 times the
// radius of its control points at their angles, so these get the radius
// c * 6 / (4 + 2 cos(pi / (2 n))) and the curve meets the circle there.
// Neither spline is the circle: they deviate most near their ends (the
// end conditions), the test prints by how much.
//
// The bore's points are the shaft's scaled by (b - delta) / b, so the
// two contact curves are the same spline up to the scaling, and the
// interference is delta along them to that factor.
b = 10;
c = 20;
delta = 0.001;
h_arc = 0.5;         // element size on the contact surfaces
h_centre = 1;        // element size in the shaft's centre
h_outer = 1;         // element size at the hub's outer surface
n_contact = 4096;    // intervals of the contact splines
n_outer = 128;       // intervals of the outer B-spline

Point(1) = {0, 0, 0, h_centre};

// Points at the angles pi/2 i/n on the circle of radius R, the ends exactly
// on the axes; their tags in p[].
Macro CirclePoints
  p[] = {};
  For i In {0:n}
    If (i == 0)
      x = R; y = 0;
    ElseIf (i == n)
      x = 0; y = R;
    Else
      x = R * Cos(Pi / 2 * i / n); y = R * Sin(Pi / 2 * i / n);
    EndIf
    p[i] = newp;
    Point(p[i]) = {x, y, 0, lc};
  EndFor
Return

// Shaft: a quarter disc.
R = b; lc = h_arc; n = n_contact;
Call CirclePoints;
shaft[] = p[];
Spline(1) = shaft[];
Line(2) = {shaft[n_contact], 1};
Line(3) = {1, shaft[0]};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// Hub: a quarter annulus.
R = b - delta; lc = h_arc; n = n_contact;
Call CirclePoints;
bore[] = p[];
Spline(11) = bore[];
R = c; lc = h_outer; n = n_outer;
Call CirclePoints;
outer[] = p[];
// The B-spline's inner control points pushed out (see above).
f = 6 / (4 + 2 * Cos(Pi / (2 * n)));
For i In {1:n - 1}
  Translate {(f - 1) * c * Cos(Pi / 2 * i / n),
             (f - 1) * c * Sin(Pi / 2 * i / n), 0} { Point{outer[i]}; }
EndFor
BSpline(21) = outer[];
Line(12) = {bore[0], outer[0]};
Line(13) = {outer[n_outer], bore[n_contact]};
Curve Loop(2) = {12, 21, 13, -11};
Plane Surface(2) = {2};

Physical Surface("shaft") = {1};
Physical Surface("hub") = {2};
Physical Curve("shaft surface") = {1};
Physical Curve("hub bore") = {11};
Physical Curve("hub outer surface") = {21};
Physical Curve("x axis") = {3, 12};
Physical Curve("y axis") = {2, 13};
