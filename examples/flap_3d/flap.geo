// An elastic flap in a 3D channel: the duct [0, 1] x [0, 0.4] x [0, 0.4] (flow along x, no-slip
// walls at y = 0, 0.4 and z = 0, 0.4) with the flap [0.35, 0.4] x [0, 0.25] x [0.1, 0.3]
// standing on its floor cut out: the fluid (tet10 with order 2); and the flap as a volume of
// its own (own nodes; 2 x 2 x 2 hexahedra, hex27), clamped at y = 0. The fluid's hole
// (`flap_wet_fluid`) and the flap's five free faces (`wet`) meet at an fsi interface, with
// non-matching facets (tri6 on the fluid, quad9 on the flap).
//   h: the fluid's cell size away from the flap; hf: on the flap.
h = 0.1;
hf = 0.05;
SetFactory("OpenCASCADE");
x0 = 0.35; t = 0.05; ht = 0.25; z0 = 0.1; w = 0.2;
Box(1) = {0, 0, 0, 1, 0.4, 0.4};
Box(2) = {x0, 0, z0, t, ht, w};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
e = 1e-6;
Physical Volume("fluid") = {3};
Physical Surface("inflow") = {Surface In BoundingBox{-e, -e, -e, e, 0.4 + e, 0.4 + e}};
Physical Surface("outflow") = {Surface In BoundingBox{1 - e, -e, -e, 1 + e, 0.4 + e, 0.4 + e}};
Physical Surface("walls") = {Surface In BoundingBox{-e, -e, -e, 1 + e, e, 0.4 + e},
                             Surface In BoundingBox{-e, 0.4 - e, -e, 1 + e, 0.4 + e, 0.4 + e},
                             Surface In BoundingBox{-e, -e, -e, 1 + e, 0.4 + e, e},
                             Surface In BoundingBox{-e, -e, 0.4 - e, 1 + e, 0.4 + e, 0.4 + e}};
Physical Surface("flap_wet_fluid") = {Surface In BoundingBox{x0 - e, -e, z0 - e, x0 + t + e,
                                                             ht + e, z0 + w + e}};
// The flap, made after the fluid's groups (its faces lie on the fluid's hole): an OpenCASCADE
// box's faces are x min, x max, y min, y max, z min, z max.
Box(4) = {x0, 0, z0, t, ht, w};
s[] = Boundary{Volume{4};};
Physical Volume("flap") = {4};
Physical Surface("clamped") = {s[2]};
Physical Surface("wet") = {s[0], s[1], s[3], s[4], s[5]};
c[] = Boundary{Surface{s[]};};
Transfinite Curve{c[]} = 3;
Transfinite Surface{s[]};
Recombine Surface{s[]};
Transfinite Volume{4};
MeshSize{PointsOf{Volume{3};}} = h;
MeshSize{Point In BoundingBox{x0 - e, -e, z0 - e, x0 + t + e, ht + e, z0 + w + e}} = hf;
