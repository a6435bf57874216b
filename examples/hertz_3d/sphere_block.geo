// Quarter of the lower half of an elastic sphere of radius R (centre (0, 0, R)) resting on an
// elastic block [0, L] x [0, L] x [-H, 0] at the origin; symmetry planes x = 0 and y = 0.
// Two independent tetrahedral meshes (curved against flat: non-matching), both graded towards
// the first contact point: size hc within r0 of it, growing linearly (rate grad) to hmax.
SetFactory("OpenCASCADE");
refine = 1;            // 2 halves every element size; 0.5 doubles it
R = 1;
L = 2;
H = 2;
hc = 0.02 / refine;    // element size in the contact zone
hmax = 0.4 / refine;   // element size far from it
r0 = 0.2;              // radius of the uniformly fine zone
grad = 0.5;            // growth of the element size per unit distance beyond r0

Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi/2};
Box(2) = {0, 0, -H, L, L, H};
eps = 1e-6 * R;
top() = Surface In BoundingBox{-eps, -eps, R - eps, R + eps, R + eps, R + eps};
symx() = Surface In BoundingBox{-eps, -eps, -H - eps, eps, L + eps, R + eps};
symy() = Surface In BoundingBox{-eps, -eps, -H - eps, L + eps, eps, R + eps};
btop() = Surface In BoundingBox{-eps, -eps, -eps, L + eps, L + eps, eps};
bottom() = Surface In BoundingBox{-eps, -eps, -H - eps, L + eps, L + eps, -H + eps};
ball() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, R + eps, R + eps};
ball() -= {top(), symx(), symy(), btop()};

Field[1] = MathEval;
Field[1].F = Sprintf("Min(%g, %g + %g*Max(0, Sqrt(x*x + y*y + z*z) - %g))", hmax, hc, grad, r0);
Background Field = 1;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
Mesh.MeshSizeExtendFromBoundary = 0;

Physical Surface("surface") = {ball()};
Physical Surface("block_top") = {btop()};
Physical Surface("top") = {top()};
Physical Surface("bottom") = {bottom()};
Physical Surface("symmetry_x") = {symx()};
Physical Surface("symmetry_y") = {symy()};
Physical Volume("sphere") = {1};
Physical Volume("block") = {2};
