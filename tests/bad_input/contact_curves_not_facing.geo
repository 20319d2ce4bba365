// The seed's two blocks with the upper one moved sideways past the lower
// one: its contact curve [250, 350] x {200.001} faces no part of body 2's
// [0, 200] x {200} (issue 21 item 12).
// The two surfaces are meshed independently (non-matching interface).
h_upper = 12.5;
h_lower = 25;
Point(1) = {0, 0, 0, h_lower};
Point(2) = {200, 0, 0, h_lower};
Point(3) = {200, 200, 0, h_lower};
Point(4) = {0, 200, 0, h_lower};
Point(11) = {250, 200.001, 0, h_upper};
Point(12) = {350, 200.001, 0, h_upper};
Point(13) = {350, 300.001, 0, h_upper};
Point(14) = {250, 300.001, 0, h_upper};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};
Physical Surface("body 1") = {2};
Physical Surface("body 2") = {1};
Physical Curve("dirichlet") = {1};
Physical Curve("traction") = {13};
Physical Curve("contact") = {3, 11};
