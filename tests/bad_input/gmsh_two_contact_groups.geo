// Two physical curves named "contact" (the second with its own tag).
// Otherwise the two stacked unit squares of missing_contact_group.geo.
h = 0.3;
Point(1) = {0, 0, 0, h};
Point(2) = {1, 0, 0, h};
Point(3) = {1, 1, 0, h};
Point(4) = {0, 1, 0, h};
Point(5) = {1, 2, 0, h};
Point(6) = {0, 2, 0, h};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {3, 5};
Line(6) = {5, 6};
Line(7) = {6, 4};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -3};
Plane Surface(2) = {2};
Physical Surface("body 1") = {2};
Physical Surface("body 2") = {1};
Physical Curve("dirichlet") = {1, 2, 4};
Physical Curve("traction") = {6};
Physical Curve("contact") = {3};
Physical Curve("contact", 20) = {5};
