// A wedge of half-angle A (degrees) pressed tip-first onto a block
// (tests/bad_input/CMakeLists.txt: the mortar pairs segments facing
// within 60 degrees; the flanks meet the block at 90 - A degrees from
// facing). Wedge: tip (100, 200), flanks 40 mm high, top at y = 260.
A = 25;
h = 5;
H = 40;
w = H * Tan(A * Pi / 180);
Point(1) = {0, 0, 0, 20};
Point(2) = {200, 0, 0, 20};
Point(3) = {200, 200, 0, 20};
Point(4) = {0, 200, 0, 20};
Point(5) = {100, 200, 0, h};
Point(11) = {100, 200, 0, h};
Point(12) = {100 + w, 200 + H, 0, h};
Point(13) = {100 + w, 260, 0, h};
Point(14) = {100 - w, 260, 0, h};
Point(15) = {100 - w, 200 + H, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 5};
Line(4) = {5, 4};
Line(5) = {4, 1};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 15};
Line(15) = {15, 11};
Curve Loop(1) = {1, 2, 3, 4, 5};
Plane Surface(1) = {1};
Curve Loop(2) = {11, 12, 13, 14, 15};
Plane Surface(2) = {2};
Physical Surface("body 1") = {2};
Physical Surface("body 2") = {1};
Physical Curve("dirichlet") = {1};
Physical Curve("traction") = {13};
Physical Curve("contact") = {11, 15, 3, 4};
