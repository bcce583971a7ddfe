//! Five-axis minimum-time trajectories: quintic intervals, exact per-interval minimum time, knot optimisation, the paper's GA baseline, deflection replanning.
