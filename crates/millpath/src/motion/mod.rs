//! Motion planning: jerk-limited profiles, look-ahead planner, sampling and limit verification.

pub mod five_axis;
pub mod limits;
pub mod path;
pub mod plan;
pub mod profile;
pub mod sample;
pub mod table2;
pub mod verify;

pub use plan::{BlockPlan, Plan, PlanOptions, Span, plan_moves, plan_toolpath, plan_toolpath_opt};
pub use sample::Sample;
