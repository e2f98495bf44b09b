// A linear (4-node tetrahedra) mesh, which the readers refuse.
// box_tet4_v41.msh: gmsh -3 -format msh41.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.01, 0.01, 0.01};
Physical Volume("block") = {1};
Mesh.MeshSizeMin = 0.01;
Mesh.MeshSizeMax = 0.01;
