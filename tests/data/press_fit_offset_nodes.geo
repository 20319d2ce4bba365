// prm/meshes/press_fit.geo with a finer bore (element size 0.45 mm against
// the shaft's 0.5 mm): the nodes of the two contact surfaces lie at
// different angles.
h_bore = 0.45;
Include "../../prm/meshes/press_fit.geo";
