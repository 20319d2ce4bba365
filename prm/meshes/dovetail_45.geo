// prm/meshes/dovetail.geo with flanks at 45 degrees to the tangential
// direction instead of 30: tan 45 = 1 lies above mu = 0.5, so no node of
// the flanks can stick under the centrifugal load, and the wedge of the
// two flanks alone holds the blade (tests/dovetail_45). Gmsh reads an
// included file from the including file's directory.
alpha = 45;
Include "dovetail.geo";
