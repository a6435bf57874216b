// A 1 x 1 x 4 bar of 3 x 3 x 12 tri-quadratic hexahedra (hex27).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 4, 1, 1};
For c In {1:12}
  bb() = BoundingBox Curve{c};
  If (Fabs(bb(3) - bb(0)) > 1e-5)
    Transfinite Curve{c} = 13;
  Else
    Transfinite Curve{c} = 4;
  EndIf
EndFor
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{1};
Physical Surface("fixed") = {1};   // x = 0
Physical Surface("twisted") = {2}; // x = 4
Physical Volume("bar") = {1};
Mesh.ElementOrder = 2;
