// rings.geo with the rings 0.1 apart instead of 0.2 (s = 0.05) and 0.05 above the floor
// (rings200.yaml): the right wall is at x = 2 k (R + s) + 2 s = 21.1.
s = 0.05;
Include "rings.geo";
