// Press (shrink) fit, theory.md section 9: a solid shaft of radius b in a
// hub of inner radius b - delta and outer radius c. The two surfaces
// overlap by the radial interference delta; the contact pushes them apart.
//
// The whole cross-section, held at points where the axisymmetric solution
// does not move in the held direction: the shaft at its centre (x and y)
// and at (b/2, 0) (y), the hub at (c, 0) and (-c, 0) (y) and at (0, c) (x).
// These supports hold each body's three rigid motions and no more, so
// (nothing else loading the pair) they carry no force and leave the
// solution as if the pair floated. (prm/meshes/press_fit_quarter.geo is
// the quarter model with rollers on the symmetry lines, which hold the
// end nodes of the slave contact surface along the surface.)
//
// The shaft's surface and the hub's bore get the same element size, hence
// (their lengths differ by 2 pi delta) the same number of nodes at the
// same angles. P1 needs it: its circles are polygons, whose chord sag
// h^2 / (8 r) is larger than a realistic delta, and nodes at different
// angles would turn the sag into a spurious gap. P2 does not: its faces
// are parabolas through a point on the circle (the circles are manifolds
// of the mesh), and the mortar integrates on them (set h_bore before
// including this file to try; tests/press_fit does).
b = 10;
c = 20;
delta = 0.001;
h_arc = 0.5;         // element size on the contact surfaces
If (!Exists(h_bore))
  h_bore = h_arc;    // element size on the hub's bore
EndIf
h_centre = 1;        // element size in the shaft's centre
h_outer = 1;         // element size at the hub's outer surface

// Shaft: a disc of 4 quarter circles, its centre and (b/2, 0) embedded.
Point(1) = {0, 0, 0, h_centre};
Point(2) = {b, 0, 0, h_arc};
Point(3) = {0, b, 0, h_arc};
Point(4) = {-b, 0, 0, h_arc};
Point(5) = {0, -b, 0, h_arc};
Point(6) = {b / 2, 0, 0, h_centre};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{1, 6} In Surface{1};

// Hub: an annulus.
r = b - delta;
Point(11) = {r, 0, 0, h_bore};
Point(12) = {0, r, 0, h_bore};
Point(13) = {-r, 0, 0, h_bore};
Point(14) = {0, -r, 0, h_bore};
Point(21) = {c, 0, 0, h_outer};
Point(22) = {0, c, 0, h_outer};
Point(23) = {-c, 0, 0, h_outer};
Point(24) = {0, -c, 0, h_outer};
Circle(11) = {11, 1, 12};
Circle(12) = {12, 1, 13};
Circle(13) = {13, 1, 14};
Circle(14) = {14, 1, 11};
Circle(21) = {21, 1, 22};
Circle(22) = {22, 1, 23};
Circle(23) = {23, 1, 24};
Circle(24) = {24, 1, 21};
Curve Loop(2) = {21, 22, 23, 24};
Curve Loop(3) = {11, 12, 13, 14};
Plane Surface(2) = {2, 3};

Physical Surface("shaft") = {1};
Physical Surface("hub") = {2};
Physical Curve("shaft surface") = {1, 2, 3, 4};
Physical Curve("hub bore") = {11, 12, 13, 14};
Physical Curve("hub outer surface") = {21, 22, 23, 24};
Physical Point("shaft centre") = {1};
Physical Point("shaft on x axis") = {6};
Physical Point("hub on x axis") = {21, 23};
Physical Point("hub on y axis") = {22};
