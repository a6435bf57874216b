// Elastic rings in a staggered pile above a box (examples/rings/rings.yaml).
//
// Parameters: N rings in rows of k and k - 1 (alternating, shifted by half a pitch), each of
// outer radius R and inner radius r, meshed with nc quadrilaterals per quarter circle and nr
// through the wall. The rings are 2 (R + s) apart (s: half the gap between neighbours), the
// lowest row s above the floor y = 0; the box's walls are x = 0 and x = W = 2 k (R + s) + 2 s,
// so the rings of a full row just fit between them. A file that sets s before
// `Include "rings.geo";` keeps its value (rings200.geo).
N = 200; k = 10;
nc = 6; nr = 2;
R = 1.0; r = 0.8;
If (!Exists(s)) s = 0.1; EndIf
p = 2 * (R + s);             // pitch within a row
h = p * Sqrt(3) / 2;         // pitch between rows: neighbours of adjacent rows touch at 2 s
outer[] = {}; inner[] = {}; cells[] = {};
i = 0;
For row In {0 : Ceil(2 * N / (2 * k - 1))}
  m = k - Fmod(row, 2);         // rings in this row
  For j In {0 : m - 1}
    If (i < N)
      cx = 2 * s + R + s + j * p + Fmod(row, 2) * p / 2; cy = R + s + row * h;
      o = 100 * i;           // tag offset of ring i
      Point(o + 1) = {cx, cy, 0};
      Point(o + 2) = {cx + R, cy, 0}; Point(o + 3) = {cx, cy + R, 0};
      Point(o + 4) = {cx - R, cy, 0}; Point(o + 5) = {cx, cy - R, 0};
      Point(o + 6) = {cx + r, cy, 0}; Point(o + 7) = {cx, cy + r, 0};
      Point(o + 8) = {cx - r, cy, 0}; Point(o + 9) = {cx, cy - r, 0};
      For q In {0 : 3}
        Circle(o + 1 + q) = {o + 2 + q, o + 1, o + 2 + Fmod(q + 1, 4)};
        Circle(o + 5 + q) = {o + 6 + q, o + 1, o + 6 + Fmod(q + 1, 4)};
        Line(o + 9 + q) = {o + 6 + q, o + 2 + q};
      EndFor
      For q In {0 : 3}
        Curve Loop(o + 1 + q) = {o + 9 + q, o + 1 + q, -(o + 9 + Fmod(q + 1, 4)), -(o + 5 + q)};
        Plane Surface(o + 1 + q) = {o + 1 + q};
      EndFor
      Transfinite Curve{o + 1 : o + 8} = nc + 1;
      Transfinite Curve{o + 9 : o + 12} = nr + 1;
      Transfinite Surface{o + 1 : o + 4}; Recombine Surface{o + 1 : o + 4};
      outer[] += {o + 1 : o + 4}; inner[] += {o + 5 : o + 8}; cells[] += {o + 1 : o + 4};
      i += 1;
    EndIf
  EndFor
EndFor
Physical Surface("rings") = {cells[]};
Physical Curve("outer") = {outer[]};
Physical Curve("inner") = {inner[]};
