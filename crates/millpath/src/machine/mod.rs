//! Machines: per-axis limits, presets, TOML profiles, kinematics.

pub mod kinematics;
