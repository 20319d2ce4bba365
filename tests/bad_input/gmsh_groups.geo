// Two stacked unit squares with named groups, for the bad-input cases of the
// gmsh scene's per-group entries: body 1 = 'upper' = [0,1] x [1,2],
// body 2 = 'lower' = [0,1] x [0,1], meshed independently.
h = 0.5;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Point(11) = {0, 1, 0, h};
Point(12) = {1, 1, 0, h};
Point(13) = {1, 2, 0, h};
Point(14) = {0, 2, 0, h};
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
Physical Surface("upper") = {2};
Physical Surface("lower") = {1};
Physical Surface("both squares") = {1, 2};
Physical Curve("base") = {1};
Physical Curve("base again") = {1};
Physical Curve("upper top") = {13};
Physical Curve("upper bottom") = {11};
Physical Curve("upper bottom again") = {11};
Physical Curve("lower top") = {3};
Physical Point("corner") = {1};
