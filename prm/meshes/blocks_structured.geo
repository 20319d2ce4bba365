// The seed's two blocks (theory.md section 5) with the built-in 'blocks'
// scene's default quadrilateral meshes: upper block [50,150] x [200,300] in
// 4 x 4 cells, lower block [0,200] x [0,200] in 8 x 8. gmsh meshes 2 x 2 and
// 4 x 4 structured quadrangles, which the program's quadrilateral reading
// (recombine, subdivide once) turns into 4 x 4 and 8 x 8: the same
// vertices as the built-in scene. Physical groups named for the gmsh
// scene's per-group entries (prm/blocks_gmsh.prm).
Point(1) = {0, 0, 0};
Point(2) = {200, 0, 0};
Point(3) = {200, 200, 0};
Point(4) = {0, 200, 0};
Point(11) = {50, 200, 0};
Point(12) = {150, 200, 0};
Point(13) = {150, 300, 0};
Point(14) = {50, 300, 0};
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
Transfinite Curve{1, 2, 3, 4} = 5;
Transfinite Curve{11, 12, 13, 14} = 3;
Transfinite Surface{1, 2};
Recombine Surface{1, 2};

Physical Surface("upper block") = {2};
Physical Surface("lower block") = {1};
Physical Curve("base") = {1};
Physical Curve("loaded top") = {13};
Physical Curve("upper block bottom") = {11};
Physical Curve("lower block top") = {3};
