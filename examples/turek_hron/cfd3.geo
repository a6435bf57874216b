// Turek-Hron CFD3 (Turek & Hron 2006): the channel of fsi.geo with cylinder and flag both rigid,
// the fluid alone (structure = 0): the flag's wet boundary `flag_wet_fluid` is a no-slip wall.
// `wall` refines the fluid's facets on cylinder and flag to hc / wall (hc = 0.0175 at
// refine 1), growing back to hc within 0.02 of them; the rest of the mesh is fsi.geo's.
If (!Exists(wall))
  wall = 1;
EndIf
structure = 0;
Include "fsi.geo";
