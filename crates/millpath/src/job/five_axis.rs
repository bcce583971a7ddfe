//! The five-axis job behind `millpath five-axis`: the machine's kinematics by name (with the
//! structural overrides of a limits file: tool length, the paper machine's z1 and z2) and the
//! poses of the paper's case or of a path file, each pose checked reachable; planning itself
//! is [`crate::motion::five_axis::plan`].

use crate::geom::Point3;
use crate::machine::kinematics::{HeadHead, Kinematics, PaperAb, Pose, TableTable, TrtKind};
use crate::motion::five_axis::case::{self, LimitsFile};
use crate::{Error, InputError};

/// The machines [`kinematics`] takes.
pub const MACHINES: &[&str] = &["paper", "xyzac-trt", "xyzbc-trt", "head-head"];

/// The machine named `name` with the given structural overrides.
pub fn kinematics(name: &str, over: &LimitsFile) -> Result<Box<dyn Kinematics>, Error> {
    let only_paper = |key: &str, v: Option<f64>| -> Result<(), Error> {
        match v {
            Some(v) => Err(InputError::new(key, v)
                .at(format!("--machine {name}"))
                .expected(format!("{key} only with --machine paper"))
                .into()),
            None => Ok(()),
        }
    };
    Ok(match name {
        "paper" | "paper-ab" => {
            let mut m = PaperAb::paper();
            m.tool_length = over.tool_length.unwrap_or(m.tool_length);
            m.z1 = over.z1.unwrap_or(m.z1);
            m.z2 = over.z2.unwrap_or(m.z2);
            Box::new(m)
        }
        "xyzac-trt" | "ac-trt" | "xyzbc-trt" | "bc-trt" => {
            only_paper("z1", over.z1)?;
            only_paper("z2", over.z2)?;
            let kind = if name.contains("ac") {
                TrtKind::Ac
            } else {
                TrtKind::Bc
            };
            let mut m = TableTable::typical(kind);
            m.tool_offset = over.tool_length.unwrap_or(m.tool_offset);
            Box::new(m)
        }
        "head-head" => {
            only_paper("z1", over.z1)?;
            only_paper("z2", over.z2)?;
            let mut m = HeadHead::typical();
            m.length = over.tool_length.unwrap_or(m.length);
            Box::new(m)
        }
        other => {
            return Err(InputError::new("machine", other)
                .at("--machine")
                .expected("paper, xyzac-trt, xyzbc-trt or head-head")
                .into());
        }
    })
}

/// The poses to plan: `case` (only `paper`) or a path file's text `(text, name)`, each pose
/// checked reachable on `kin` (the error names its line); with the case's default deflection.
pub fn poses(
    case_name: Option<&str>,
    path: Option<(&str, &str)>,
    kin: &dyn Kinematics,
) -> Result<(Vec<Pose>, Option<Point3>), Error> {
    match (case_name, path) {
        (Some("paper"), _) => Ok((case::paper_path(), Some(case::paper_deflection()))),
        (Some(c), _) => Err(InputError::new("case", c)
            .at("--case")
            .expected("paper")
            .into()),
        (None, Some((text, name))) => {
            let lines = case::parse_path_csv_lines(text, name)?;
            // Every pose must be reachable: name its line.
            for (line, pose) in &lines {
                kin.inverse(pose)
                    .map_err(|e| e.at(format!("{name}:{line}")))?;
            }
            Ok((lines.into_iter().map(|(_, p)| p).collect(), None))
        }
        (None, None) => Err(InputError::new("input", "none")
            .expected("--case paper or a path file")
            .into()),
    }
}
