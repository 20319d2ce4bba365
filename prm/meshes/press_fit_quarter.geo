// Press (shrink) fit, theory.md section 9, as a quarter model: the quarter
// x >= 0, y >= 0 of a solid shaft of radius b in a hub of inner radius
// b - delta and outer radius c (prm/meshes/press_fit.geo is the whole
// cross-section). The two surfaces overlap by the radial interference
// delta; the contact pushes them apart.
//
// The symmetry lines carry rollers (prm/press_fit_quarter.prm): the
// curves on the x axis ("x axis", both bodies) fix u_y, those on the y
// axis ("y axis") fix u_x. The hub's bore ends on them, so its two end
// nodes are contact nodes with a roller; the fixed component is the one
// along the contact surface there, which replaces the tangential contact
// condition (doc/contact.md section 2), and the normal condition stays.
//
// The shaft's surface and the hub's bore get the same element size, hence
// the same number of nodes at the same angles, which P1 needs (its
// circles are polygons; prm/meshes/press_fit.geo says why). P2 does not.
b = 10;
c = 20;
delta = 0.001;
h_arc = 0.5;         // element size on the contact surfaces
h_centre = 1;        // element size in the shaft's centre
h_outer = 1;         // element size at the hub's outer surface

// Shaft: a quarter disc.
Point(1) = {0, 0, 0, h_centre};
Point(2) = {b, 0, 0, h_arc};
Point(3) = {0, b, 0, h_arc};
Circle(1) = {2, 1, 3};
Line(2) = {3, 1};
Line(3) = {1, 2};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

// Hub: a quarter annulus.
r = b - delta;
Point(11) = {r, 0, 0, h_arc};
Point(12) = {0, r, 0, h_arc};
Point(21) = {c, 0, 0, h_outer};
Point(22) = {0, c, 0, h_outer};
Circle(11) = {11, 1, 12};
Circle(21) = {21, 1, 22};
Line(12) = {11, 21};
Line(13) = {22, 12};
Curve Loop(2) = {12, 21, 13, -11};
Plane Surface(2) = {2};

Physical Surface("shaft") = {1};
Physical Surface("hub") = {2};
Physical Curve("shaft surface") = {1};
Physical Curve("hub bore") = {11};
Physical Curve("hub outer surface") = {21};
Physical Curve("x axis") = {3, 12};
Physical Curve("y axis") = {2, 13};
