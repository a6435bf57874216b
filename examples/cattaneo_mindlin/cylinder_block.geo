// Cattaneo-Mindlin partial slip in plane strain: the lower half of an elastic cylinder
// (radius R, centre (0, R)) on an elastic block [-L, L] x [-H, 0] of the same material.
// Both meshes are graded towards the first contact point, independently (non-matching):
// element size hc within r0 of it, growing linearly (rate grad) to hmax.
refine = 1;            // 2 halves every element size
R = 1; L = 2; H = 2;
hc = 0.006 / refine;
hmax = 0.25 / refine;
r0 = 0.15;
grad = 0.4;
Point(1) = {0, 0, 0};
Point(2) = {0, R, 0};
Point(3) = {R, R, 0};
Point(4) = {-R, R, 0};
Circle(1) = {4, 2, 1};
Circle(2) = {1, 2, 3};
Line(3) = {3, 4};
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};
Point(11) = {-L, -H, 0};
Point(12) = {L, -H, 0};
Point(13) = {L, 0, 0};
Point(14) = {-L, 0, 0};
Line(11) = {11, 12};
Line(12) = {12, 13};
Line(13) = {13, 14};
Line(14) = {14, 11};
Curve Loop(2) = {11, 12, 13, 14};
Plane Surface(2) = {2};
Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g*Max(0, Sqrt(x*x + y*y) - %g))", hmax, hc, grad, r0);
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.Algorithm = 6;
Recombine Surface{1, 2};
Mesh.RecombinationAlgorithm = 1;
Physical Curve("surface") = {1, 2};
Physical Curve("top") = {3};
Physical Curve("block_top") = {13};
Physical Curve("bottom") = {11};
Physical Surface("cylinder") = {1};
Physical Surface("block") = {2};
