// The right half x >= 100 of prm/meshes/blocks_structured.geo (the seed's
// two blocks, symmetric about x = 100): the same vertices as the whole
// model's right half after the program's quadrilateral reading (recombine,
// subdivide once): upper block [100, 150] x [200, 300] in 2 x 4 cells,
// lower block [100, 200] x [0, 200] in 4 x 8. The symmetry line x = 100
// ("symmetry line", both bodies) ends on the contact surfaces: the upper
// block's contact node (100, 200) carries its roller. tests/contact_roller.
Point(1) = {100, 0, 0};
Point(2) = {200, 0, 0};
Point(3) = {200, 200, 0};
Point(4) = {100, 200, 0};
Point(11) = {100, 200, 0};
Point(12) = {150, 200, 0};
Point(13) = {150, 300, 0};
Point(14) = {100, 300, 0};
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
Transfinite Curve{1, 3} = 3;
Transfinite Curve{2, 4} = 5;
Transfinite Curve{11, 13} = 2;
Transfinite Curve{12, 14} = 3;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};
Physical Surface("upper block") = {2};
Physical Surface("lower block") = {1};
Physical Curve("base") = {1};
Physical Curve("loaded top") = {13};
Physical Curve("upper block bottom") = {11};
Physical Curve("lower block top") = {3};
Physical Curve("symmetry line") = {4, 14};
