// Two hollow tori of the seed paper's proportions (major radius 76, minor radius 24, wall
// thickness 4.5), each closed into a full ring: torus A lies in the plane z = 0 around the
// z axis; torus B stands upright in the plane y = 0 around an axis parallel to y through
// (xb, 0, 0), its lowest point of the rim facing A's outer equator across a gap g. Their
// tubes meet crosswise: a point contact that spreads as the walls flatten.
// Structured hexahedra: an annulus cross-section (nc elements per quarter of the tube's
// circumference, nt through the wall) swept about the torus axis in four quarter turns of
// na layers each. nc, nt, na and g may be set before this file is included.
Ra = 76;  r = 24;  w = 4.5;
If (!Exists(nc)) nc = 6; EndIf
If (!Exists(nt)) nt = 1; EndIf
If (!Exists(na)) na = 12; EndIf
If (!Exists(g)) g = 2; EndIf
ri = r - w;
xb = 2 * (Ra + r) + g;  // B's centre: its rim (xb - Ra - r) faces A's equator (Ra + r)

// Macro HollowTorus: annulus centred at (px, py, pz) in the plane spanned by e1 (radial) and e2,
// swept about the axis (ax, ay, az) through (ox, oy, oz). Returns its volumes in vols[],
// its outer and inner surfaces in outs[] and ins[].
Macro HollowTorus
  c = newp; Point(c) = {px, py, pz};
  p[] = {};
  For k In {0:3}
    ca = Cos(k * Pi / 2); sa = Sin(k * Pi / 2);
    p[k] = newp;
    Point(p[k]) = {px + r * (ca * e1x + sa * e2x), py + r * (ca * e1y + sa * e2y), pz + r * (ca * e1z + sa * e2z)};
    p[k + 4] = newp;
    Point(p[k + 4]) = {px + ri * (ca * e1x + sa * e2x), py + ri * (ca * e1y + sa * e2y), pz + ri * (ca * e1z + sa * e2z)};
  EndFor
  oc[] = {}; ic[] = {}; rc[] = {};
  For k In {0:3}
    oc[k] = newc; Circle(oc[k]) = {p[k], c, p[(k + 1) % 4]};
    ic[k] = newc; Circle(ic[k]) = {p[k + 4], c, p[(k + 1) % 4 + 4]};
    rc[k] = newc; Line(rc[k]) = {p[k + 4], p[k]};
  EndFor
  s[] = {};
  For k In {0:3}
    cl = newll; Curve Loop(cl) = {rc[k], oc[k], -rc[(k + 1) % 4], -ic[k]};
    s[k] = news; Plane Surface(s[k]) = {cl};
    Transfinite Curve{oc[k], ic[k]} = nc + 1;
    Transfinite Curve{rc[k]} = nt + 1;
    Transfinite Surface{s[k]};
    Recombine Surface{s[k]};
  EndFor
  vols[] = {}; outs[] = {}; ins[] = {};
  front[] = s[];
  For q In {0:3}
    e[] = Extrude {{ax, ay, az}, {ox, oy, oz}, Pi / 2} { Surface{front[]}; Layers{na}; Recombine; };
    // per swept surface: the far face, the volume, then the lateral faces in loop order
    // (radial, outer arc, radial, inner arc)
    For k In {0:3}
      front[k] = e[6 * k];
      vols[] += e[6 * k + 1];
      outs[] += e[6 * k + 3];
      ins[] += e[6 * k + 5];
    EndFor
  EndFor
Return

// Torus A: around the z axis through the origin, cross-section in the plane y = 0 at x = Ra.
px = Ra; py = 0; pz = 0; e1x = 1; e1y = 0; e1z = 0; e2x = 0; e2y = 0; e2z = 1;
ax = 0; ay = 0; az = 1; ox = 0; oy = 0; oz = 0;
Call HollowTorus;
Physical Volume("torus_a") = {vols[]};
outa[] = outs[]; ina[] = ins[];
// Torus B: around the axis parallel to y through (xb, 0, 0), cross-section in the plane
// z = 0 at x = xb + Ra.
px = xb + Ra; py = 0; pz = 0; e1x = 1; e1y = 0; e1z = 0; e2x = 0; e2y = 1; e2z = 0;
ax = 0; ay = 1; az = 0; ox = xb; oy = 0; oz = 0;
Call HollowTorus;
Physical Volume("torus_b") = {vols[]};
Physical Surface("outer") = {outa[], outs[]};
Physical Surface("inner") = {ina[], ins[]};
