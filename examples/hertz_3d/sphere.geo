// Quarter of the lower half of a sphere of radius R: centre (0, 0, R), touching the plane
// z = 0 at the origin; symmetry planes x = 0 and y = 0, loaded through the cut z = R.
// Tetrahedra graded towards the first contact point: size hc within r0 of it, growing
// linearly (rate grad) to hmax. At the example's load the contact radius is about 0.12 R.
SetFactory("OpenCASCADE");
refine = 1;            // 2 halves every element size; 0.5 doubles it
R = 1;
hc = 0.02 / refine;    // element size in the contact zone
hmax = 0.15 / refine;  // element size far from it
r0 = 0.2;              // radius of the uniformly fine zone (> 1.5 x the contact radius)
grad = 0.5;            // growth of the element size per unit distance beyond r0

Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};
eps = 1e-6 * R;
top() = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
symx() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, R + eps};
symy() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, R + eps};
surface() = Surface{:};
surface() -= {top(), symx(), symy()};   // the spherical face

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g*Max(0, Sqrt(x*x + y*y + z*z) - %g))", hmax, hc, grad, r0);
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;

Physical Surface("surface") = {surface()};
Physical Surface("top") = {top()};
Physical Surface("symmetry_x") = {symx()};
Physical Surface("symmetry_y") = {symy()};
Physical Volume("sphere") = {1};
