// Two 10 mm cubes sharing the face x = 10 mm, fragmented so that the mesh is conforming
// there, without physical groups: one body per geometric volume.
// two_boxes_v41.msh: gmsh -3 -format msh41.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.01, 0.01, 0.01};
Box(2) = {0.01, 0, 0, 0.01, 0.01, 0.01};
BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }
Mesh.MeshSizeMin = 0.01;
Mesh.MeshSizeMax = 0.01;
Mesh.ElementOrder = 2;
