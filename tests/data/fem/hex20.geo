// A 20 x 10 x 10 mm block of 2 x 2 x 2 20-node hexahedra (transfinite, recombined,
// incomplete second order), its face x = 0 a physical surface.
// hex20_v41.msh: gmsh -3 -format msh41; hex20_v22.msh: -format msh22.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 0.02, 0.01, 0.01};
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("bar") = {1};
Physical Surface("x0") = {1};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
