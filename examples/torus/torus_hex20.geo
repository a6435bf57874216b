// The torus of torus.geo with 20-node hexahedra (torus_hex20.yaml asks for order 2,
// serendipity): one element through the wall (quadratic across it), 12 per quarter of the
// tube's circumference, 24 per quarter turn of the arch.
nc = 12;
nt = 1;
na = 24;
Include "torus.geo";
