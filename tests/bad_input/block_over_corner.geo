// Upper block [150,250] x [200,300] centred over the lower block's corner
// (200, 200): half of it overhangs, the load tips it over the edge.
h = 25;
Point(1) = {0, 0, 0, h};
Point(2) = {200, 0, 0, h};
Point(3) = {200, 200, 0, h};
Point(4) = {0, 200, 0, h};
Point(11) = {150, 200, 0, h};
Point(12) = {250, 200, 0, h};
Point(13) = {250, 300, 0, h};
Point(14) = {150, 300, 0, h};
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
