// A 20 x 10 x 30 mm block of 10-node tetrahedra with its bottom face (z = 0) as a
// physical surface. box_tet10_v41.msh: gmsh -3 -format msh41; _v22: -format msh22.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.02, 0.01, 0.03};
Physical Volume("block") = {1};
Physical Surface("bottom") = {5};
Mesh.MeshSizeMin = 0.012;
Mesh.MeshSizeMax = 0.012;
Mesh.ElementOrder = 2;
