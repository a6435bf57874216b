// Two unit cubes stacked in z and meshed independently: hexahedra below (5 x 5 x 5),
// tetrahedra above (size 0.15). Their meshes do not match at z = 1.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
Transfinite Curve{1:12} = 6;
Transfinite Surface{1:6};
Recombine Surface{1:6};
Transfinite Volume{1};
MeshSize{PointsOf{Volume{2};}} = 0.15;
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("bottom") = {5};
Physical Surface("top") = {12};
Physical Surface("lower_top") = {6};
Physical Surface("upper_bottom") = {11};
