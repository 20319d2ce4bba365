// Two feet on a block: body 1 is made of two separate squares (one
// physical surface of two plane surfaces), each loaded by 10 MPa on its
// top, on the lower block [0,200] x [0,200] clamped at its base. For
// tests/remesh_two_part_body: remeshing must keep both parts.
h = 20;
Point(1) = {0, 0, 0, h}; Point(2) = {200, 0, 0, h}; Point(3) = {200, 200, 0, h}; Point(4) = {0, 200, 0, h};
Point(11) = {30, 200, 0, h/2}; Point(12) = {70, 200, 0, h/2}; Point(13) = {70, 260, 0, h/2}; Point(14) = {30, 260, 0, h/2};
Point(21) = {130, 200, 0, h/2}; Point(22) = {170, 200, 0, h/2}; Point(23) = {170, 260, 0, h/2}; Point(24) = {130, 260, 0, h/2};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Line(21) = {21, 22}; Line(22) = {22, 23}; Line(23) = {23, 24}; Line(24) = {24, 21};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {11, 12, 13, 14}; Plane Surface(2) = {2};
Curve Loop(3) = {21, 22, 23, 24}; Plane Surface(3) = {3};
Physical Surface("body 1") = {2, 3};
Physical Surface("body 2") = {1};
Physical Curve("dirichlet") = {1};
Physical Curve("traction") = {13, 23};
Physical Curve("contact") = {3, 11, 21};
