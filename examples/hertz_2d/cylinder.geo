// Quarter of a cylinder of radius R in plane strain: centre (0, R), touching the plane y = 0
// at the origin. Symmetry line x = 0, loaded through the cut y = R by a prescribed displacement.
// The mesh is graded: element size hc within r0 of the first contact point, growing linearly
// (rate grad) to hmax away from it, so that the contact zone (half-width about 0.1 R at the
// example's load) gets some 20 elements at refine = 1.
refine = 1;            // 2 halves every element size near the contact; 0.5 doubles it
R = 1;
hc = 0.005 / refine;   // element size in the contact zone
hmax = 0.08 / refine;  // element size far from it
r0 = 0.15;             // radius of the uniformly fine zone (> 1.5 x the contact half-width)
grad = 0.4;            // growth of the element size per unit distance beyond r0

Point(1) = {0, 0, 0};      // first contact point
Point(2) = {0, R, 0};      // centre
Point(3) = {R, R, 0};
Circle(1) = {1, 2, 3};     // the curved surface, slave side of the contact
Line(2) = {3, 2};          // the cut y = R
Line(3) = {2, 1};          // symmetry line x = 0
Curve Loop(1) = {1, 2, 3};
Plane Surface(1) = {1};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g*Max(0, Sqrt(x*x + y*y) - %g))", hmax, hc, grad, r0);
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.Algorithm = 6;            // frontal-Delaunay triangles, recombined (blossom) into quads
Recombine Surface{1};
Mesh.RecombinationAlgorithm = 1;

Physical Curve("surface") = {1};
Physical Curve("top") = {2};
Physical Curve("symmetry") = {3};
Physical Surface("cylinder") = {1};
