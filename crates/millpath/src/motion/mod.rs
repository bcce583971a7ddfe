//! Motion planning: jerk-limited profiles, look-ahead planner, sampling and limit verification.

pub mod five_axis;
pub mod profile;
