// A dovetail blade root in a disc slot, run from prm/dovetail.prm: the
// whole cross-section, symmetric about x = 0, the blade's radial direction
// +y, the disc's axis far below (Scene/Gmsh/Body k/Rotation axis). Units
// mm.
//
// The blade (body 1, slave): a root 20 mm wide at its base y = 0, with a
// 2 mm vertical side and a flank at alpha to the x axis on each side up to
// a 12 mm neck, the neck and a stub of the airfoil up to y = 40 (area
// 505.24 mm^2 for alpha = 30 degrees, 512 mm^2 for 45). The disc segment
// (body 2, master): 50 mm wide, from y = -30 to its rim y = 10, with a
// slot whose flanks lie on the blade's flank lines y = 2 + (10 - |x|) t,
// t = tan(alpha), a 1 mm clearance under the root and at the neck. The
// flanks coincide along 7 <= |x| <= 10: each contact zone ends at the
// blade's lower corner (+-10, 2) on the disc's flank and at the disc's
// upper corner (+-7, 2 + 3 t) on the blade's flank, two edges of contact
// at a corner of one body on the flat of the other.
//
// Each body is two surfaces, its right half and the mirror image of it
// (x -> -x), and the left half's mesh is the right half's mirrored (gmsh's
// periodic meshes), so the mesh is symmetric about x = 0.
h_c = 0.5;    // element size on the flanks
h_b = 2;      // elsewhere in the blade
h_d = 4;      // elsewhere in the disc
// The flank angle to the x axis (degrees): 30, unless a file that includes
// this one has set it (dovetail_45.geo).
If (!Exists(alpha))
  alpha = 30;
EndIf
t = Tan(alpha * Pi / 180);

// Blade, right half, counterclockwise from the centre of the base.
Point(1) = {0, 0, 0, h_b};
Point(2) = {10, 0, 0, h_c};
Point(3) = {10, 2, 0, h_c};
Point(4) = {6, 2 + 4 * t, 0, h_c};
Point(5) = {6, 40, 0, h_b};
Point(6) = {0, 40, 0, h_b};
Line(1) = {1, 2};   // base of the root
Line(2) = {2, 3};
Line(3) = {3, 4};   // right flank
Line(4) = {4, 5};
Line(5) = {5, 6};   // tip
Line(6) = {6, 1};   // centre line
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};

// Blade, left half: the mirror image.
Point(12) = {-10, 0, 0, h_c};
Point(13) = {-10, 2, 0, h_c};
Point(14) = {-6, 2 + 4 * t, 0, h_c};
Point(15) = {-6, 40, 0, h_b};
Line(11) = {12, 1};
Line(12) = {13, 12};
Line(13) = {14, 13};  // left flank
Line(14) = {15, 14};
Line(15) = {6, 15};
Curve Loop(2) = {11, -6, 15, 14, 13, 12};
Plane Surface(2) = {2};

// Disc segment, right half, counterclockwise from the centre of its lower
// boundary.
Point(21) = {0, -30, 0, h_d};
Point(22) = {25, -30, 0, h_d};
Point(23) = {25, 10, 0, h_d};
Point(24) = {7, 10, 0, h_b};
Point(25) = {7, 2 + 3 * t, 0, h_c};
Point(26) = {11, 2 - t, 0, h_c};
Point(27) = {11, -1, 0, h_c};
Point(28) = {0, -1, 0, h_b};
Line(21) = {21, 22};  // lower boundary
Line(22) = {22, 23};  // right side
Line(23) = {23, 24};  // rim
Line(24) = {24, 25};
Line(25) = {25, 26};  // right flank of the slot
Line(26) = {26, 27};
Line(27) = {27, 28};  // bottom of the slot
Line(28) = {28, 21};  // centre line
Curve Loop(3) = {21, 22, 23, 24, 25, 26, 27, 28};
Plane Surface(3) = {3};

// Disc segment, left half: the mirror image.
Point(32) = {-25, -30, 0, h_d};
Point(33) = {-25, 10, 0, h_d};
Point(34) = {-7, 10, 0, h_b};
Point(35) = {-7, 2 + 3 * t, 0, h_c};
Point(36) = {-11, 2 - t, 0, h_c};
Point(37) = {-11, -1, 0, h_c};
Line(31) = {32, 21};
Line(32) = {33, 32};  // left side
Line(33) = {34, 33};  // rim
Line(34) = {35, 34};
Line(35) = {36, 35};  // left flank of the slot
Line(36) = {37, 36};
Line(37) = {28, 37};  // bottom of the slot
Curve Loop(4) = {31, -28, 37, 36, 35, 34, 33, 32};
Plane Surface(4) = {4};

// The left halves' meshes are the right halves' mirrored.
mirror[] = {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
Periodic Curve {11, 12, 13, 14, 15} = {1, 2, 3, 4, 5} Affine mirror[];
Periodic Curve {31, 32, 33, 34, 35, 36, 37} = {21, 22, 23, 24, 25, 26, 27} Affine mirror[];
Periodic Surface {2} = {1} Affine mirror[];
Periodic Surface {4} = {3} Affine mirror[];

Physical Surface("blade") = {1, 2};
Physical Surface("disc") = {3, 4};
Physical Curve("blade flanks") = {3, 13};
Physical Curve("slot flanks") = {25, 35};
Physical Curve("disc base") = {21, 31};
Physical Curve("disc sides") = {22, 32};
