// A 1.2 x 1.2 x 1.2 block with a cylindrical hole (radius 0.3, along z) and a cylinder that
// fills it, meshed independently: the curved interface is non-matching.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.2, 1.2, 1.2};
Cylinder(2) = {0.6, 0.6, 0, 0, 0, 1.2, 0.3};
BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};
// A new cylinder, created after the cut, so that it shares no surface with the block, and
// turned about its axis so that even its seam lies elsewhere.
Cylinder(2) = {0.6, 0.6, 0, 0, 0, 1.2, 0.3};
Rotate {{0, 0, 1}, {0.6, 0.6, 0}, Pi / 7} { Volume{2}; }
MeshSize{PointsOf{Volume{3};}} = 0.2;
MeshSize{PointsOf{Volume{2};}} = 0.11;
// The lateral surfaces of the cylinder and of the hole: the surfaces that span the height
// and lie within the cylinder's radius of its axis.
rim[] = {};
hole[] = {};
s2[] = Boundary{Volume{2};};
For i In {0:#s2[]-1}
  bb[] = BoundingBox Surface{s2[i]};
  If (bb[5] - bb[2] > 1.0)
    rim[] += s2[i];
  EndIf
EndFor
s3[] = Boundary{Volume{3};};
For i In {0:#s3[]-1}
  bb[] = BoundingBox Surface{s3[i]};
  If (bb[5] - bb[2] > 1.0 && bb[3] - bb[0] < 0.7 && bb[4] - bb[1] < 0.7)
    hole[] += s3[i];
  EndIf
EndFor
Physical Volume("matrix") = {3};
Physical Volume("fibre") = {2};
Physical Surface("rim") = rim[];
Physical Surface("hole") = hole[];
Physical Surface("bottom") = Surface In BoundingBox{-1, -1, -1e-6, 2, 2, 1e-6};
Physical Surface("top") = Surface In BoundingBox{-1, -1, 1.2 - 1e-6, 2, 2, 1.2 + 1e-6};
