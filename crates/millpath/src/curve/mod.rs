//! Free-form curves: four-point interpolating cubics, C1 blends, Catmull-Rom and periodic
//! splines, optimal flattening within a chordal tolerance, biarcs.
