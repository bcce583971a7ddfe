//! The plate job the job tests share: a plate with a pocket, two 4 mm holes and a 10 mm hole,
//! as an SVG drawing, and a job file that faces it, pockets it, bores and drills the holes
//! and cuts it out with two tabs.

#![allow(dead_code)]

use millpath::Error;
use millpath::job::part::{self, JobSpec};
use std::path::Path;

pub const PLATE: &str = r#"<svg xmlns="http://www.w3.org/2000/svg" width="80mm" height="60mm" viewBox="0 0 80 60">
  <rect x="0" y="0" width="80" height="60" rx="4"/>
  <rect x="10" y="10" width="30" height="25" rx="3"/>
  <circle cx="60" cy="15" r="2"/>
  <circle cx="60" cy="45" r="2"/>
  <circle cx="25" cy="48" r="5"/>
</svg>
"#;

pub const JOB: &str = r#"drawing = "plate.svg"
machine = "hsm"

[stock]
margin = 10.0
thickness = 4.0
top = 0.3

[[tool]]
number = 1
diameter = 6.0
feed = 1200
spindle = 12000

[[tool]]
number = 2
type = "drill"
diameter = 4.0
feed = 300
spindle = 6000

[[operation]]
type = "face"
tool = 1

[[operation]]
type = "pocket"
tool = 1
depth = 2.0
step_down = 2.0

[[operation]]
type = "bore"
tool = 1
min_diameter = 9

[[operation]]
type = "drill"
tool = 2
max_diameter = 5

[[operation]]
type = "profile"
tool = 1
step_down = 2.25
tabs = 2
"#;

/// The job file (with `edit` applied to its text) in a folder beside the plate's drawing.
pub fn spec(dir: &Path, edit: impl Fn(&str) -> String) -> Result<JobSpec, Error> {
    std::fs::write(dir.join("plate.svg"), PLATE).unwrap();
    let path = dir.join("plate.toml");
    std::fs::write(&path, edit(JOB)).unwrap();
    part::read_file(&path)
}

pub fn same(s: &str) -> String {
    s.to_owned()
}
