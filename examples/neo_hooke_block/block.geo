// A unit cube of 8 x 8 x 8 hexahedra (transfinite), with named faces.
SetFactory("OpenCASCADE");
n = 8;
Box(1) = {0, 0, 0, 1, 1, 1};
Transfinite Curve{:} = n + 1;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Volume("block") = {1};
Physical Surface("bottom") = {5};  // z = 0
Physical Surface("top") = {6};     // z = 1
Physical Surface("left") = {1};    // x = 0
Physical Surface("front") = {3};   // y = 0
