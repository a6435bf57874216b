// Half of the lower half of an elastic sphere of radius R (centre (0, 0, R)) on an elastic
// block [-L, L] x [0, L] x [-H, 0] of the same material; symmetry plane y = 0 (the tangential
// load is along x). Independent tetrahedral meshes graded towards the first contact point.
SetFactory("OpenCASCADE");
refine = 1;            // 2 halves every element size
R = 1; L = 2; H = 2;
hc = 0.02 / refine;
hmax = 0.4 / refine;
r0 = 0.25;
grad = 0.5;
Sphere(1) = {0, 0, R, R, -Pi/2, 0, Pi};
Box(2) = {-L, 0, -H, 2 * L, L, H};
eps = 1e-6 * R;
top() = Surface In BoundingBox{-R - eps, -eps, R - eps, R + eps, R + eps, R + eps};
sym() = Surface In BoundingBox{-L - eps, -eps, -H - eps, L + eps, eps, R + eps};
btop() = Surface In BoundingBox{-L - eps, -eps, -eps, L + eps, L + eps, eps};
bottom() = Surface In BoundingBox{-L - eps, -eps, -H - eps, L + eps, L + eps, -H + eps};
ball() = Surface In BoundingBox{-R - eps, -eps, -eps, R + eps, R + eps, R + eps};
ball() -= {top(), sym(), btop()};
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
Physical Surface("symmetry") = {sym()};
Physical Volume("sphere") = {1};
Physical Volume("block") = {2};
