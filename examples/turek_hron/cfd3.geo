// Turek-Hron CFD3 (Turek & Hron 2006): the channel of fsi.geo with cylinder and flag both rigid,
// the fluid alone (structure = 0): the flag's wet boundary `flag_wet_fluid` is a no-slip wall.
// fsi.geo's refine 1 with the fluid's facets on cylinder and flag three times finer
// (wall = 3: 0.0058 m, back to 0.0175 within 0.02 m) and the wake box [0.1, 1.4] x [0.1, 0.31]
// at 0.01 m: the fluid mesh of fsi3_fine.geo. With wall = 1 and wake = 0 (fsi.geo's fluid mesh)
// the flow does not shed (README.md). wall, wake and refine may be set before this file is
// included.
If (!Exists(wall))
  wall = 3;
EndIf
If (!Exists(wake))
  wake = 0.01;
EndIf
structure = 0;
Include "fsi.geo";
