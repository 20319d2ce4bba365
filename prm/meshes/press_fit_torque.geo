// Press (shrink) fit that transmits a torque, theory.md section 9: a
// hollow shaft (bore radius a0, outer radius b) in a hub of inner radius
// b - delta and outer radius c, radial interference delta. The hub's outer
// circle is clamped; the shaft is turned at its bore by a prescribed
// rotation (prm/press_fit_torque.prm), so the interface carries the torque
// by friction until the whole of it slips.
//
// As in press_fit.geo, the shaft's surface and the hub's bore get the same
// element size, hence the same number of nodes at the same angles (P1's
// polygons need it; P2's curved faces do not).
a0 = 5;
b = 10;
c = 20;
delta = 0.001;
h_arc = 0.5;         // element size on the contact surfaces
h_bore = 1;          // element size on the shaft's bore
h_outer = 1;         // element size at the hub's outer surface

// Shaft: an annulus a0 <= r <= b.
Point(1) = {0, 0, 0, h_outer};
Point(2) = {b, 0, 0, h_arc};
Point(3) = {0, b, 0, h_arc};
Point(4) = {-b, 0, 0, h_arc};
Point(5) = {0, -b, 0, h_arc};
Point(6) = {a0, 0, 0, h_bore};
Point(7) = {0, a0, 0, h_bore};
Point(8) = {-a0, 0, 0, h_bore};
Point(9) = {0, -a0, 0, h_bore};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7};
Circle(6) = {7, 1, 8};
Circle(7) = {8, 1, 9};
Circle(8) = {9, 1, 6};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(4) = {5, 6, 7, 8};
Plane Surface(1) = {1, 4};

// Hub: an annulus b - delta <= r <= c.
r = b - delta;
Point(11) = {r, 0, 0, h_arc};
Point(12) = {0, r, 0, h_arc};
Point(13) = {-r, 0, 0, h_arc};
Point(14) = {0, -r, 0, h_arc};
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
Physical Curve("shaft bore") = {5, 6, 7, 8};
Physical Curve("shaft surface") = {1, 2, 3, 4};
Physical Curve("hub bore") = {11, 12, 13, 14};
Physical Curve("hub outer surface") = {21, 22, 23, 24};
