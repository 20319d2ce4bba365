// Hertz line contact (theory.md section 6) for the gmsh scene: a half disc
// of radius R (its arc down, lowest point at the origin) on a block
// [-L, L] x [-H, 0], the geometry and mesh grading of the built-in 'hertz'
// scene on triangles (source/scenes/hertz.cc writes the same file): element
// size h_min = 0.1 a within 1.5 a of the first contact point, growing
// linearly to R/4 away from it, where a is Hertz's half-width for the line
// load P' and E* (plane strain, both bodies E = 130 000 MPa, nu = 0.3).
// The arc is a gmsh Circle: the scene keeps it round (a manifold) under
// refinement and with curved P2 faces.
R = 100;  L = 100;  H = 100;
P = 1000;                              // line load P' (N/mm)
E = 130000;  nu = 0.3;
E_star = E / (2 * (1 - nu * nu));
a = Sqrt(4 * P * R / (Pi * E_star));   // Hertz half-width (mm)
h_min = 0.1 * a;
h_max = R / 4;
zone = 1.5 * a;

Point(1) = {0, R, 0};   Point(2) = {-R, R, 0};
Point(3) = {0, 0, 0};   Point(4) = {R, R, 0};
Circle(1) = {2, 1, 3};  Circle(2) = {3, 1, 4};
Line(3) = {4, 1};       Line(9) = {1, 2};
Curve Loop(1) = {1, 2, 3, 9};
Plane Surface(1) = {1};
// The axis, embedded as in the built-in scene (which holds its nodes), so
// that both scenes mesh alike. Two points on it hold the disc sideways
// here (frictionless, nothing else does): x fixed at the disc's centre
// and at the axis node nearest to R/2 (gmsh puts nodes on the embedded
// line; the point splits it there).
Point(10) = {0, R / 2, 0};
Line(10) = {1, 10};  Line(11) = {10, 3};
Line{10, 11} In Surface{1};

Point(5) = {-L, -H, 0}; Point(6) = {L, -H, 0};
Point(7) = {L, 0, 0};   Point(8) = {-L, 0, 0};
Point(9) = {0, 0, 0};
Line(4) = {5, 6}; Line(5) = {6, 7}; Line(6) = {7, 9};
Line(7) = {9, 8}; Line(8) = {8, 5};
Curve Loop(2) = {4, 5, 6, 7, 8};
Plane Surface(2) = {2};

Physical Surface("disc") = {1};
Physical Surface("block") = {2};
Physical Curve("arc") = {1, 2};
Physical Curve("disc top") = {3, 9};
Physical Curve("block top") = {6, 7};
Physical Curve("base") = {4};
Physical Point("disc axis") = {1, 10};

Field[1] = Distance;  Field[1].PointsList = {3, 9};
Field[2] = Threshold; Field[2].InField = 1;
Field[2].SizeMin = h_min;  Field[2].SizeMax = h_max;
Field[2].DistMin = zone;   Field[2].DistMax = zone + 4 * (h_max - h_min);
Background Field = 2;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
