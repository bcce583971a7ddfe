//! Pocket outlines as JSON, and the loop classification every importer shares
//! ([`classify`]: every closed outline of a drawing nested into pockets and islands by
//! `crate::geom::nesting`).
//!
//! Schema (lengths in mm unless `"units": "in"`; a vertex is `[x, y]` or `[x, y, bulge]`, the
//! bulge being `tan(θ/4)` of the arc of sweep θ that leaves the vertex, positive
//! counter-clockwise):
//!
//! ```json
//! { "units": "mm",
//!   "outline": [[0, 0], [100, 0, 0.4142], [110, 10], [110, 60], [0, 60]],
//!   "islands": [ [[40, 20], [60, 20], [60, 40], [40, 40]] ] }
//! ```
//!
//! The outline must be closed implicitly (the last vertex joins the first; a repeated first
//! vertex at the end is dropped). Windings are normalised: outer counter-clockwise, islands
//! clockwise.

use crate::error::InputError;
use crate::geom::nesting::{self, Pocket};
use crate::geom::{Outline, Point};
use serde::Deserialize;

/// The pockets of a drawing, windings normalised: the first (largest) in `outer` and
/// `islands`, the others in `others` (by decreasing area, see `crate::geom::nesting`).
#[derive(Debug, Clone)]
pub struct Loops {
    /// The first pocket's boundary, counter-clockwise.
    pub outer: Outline,
    /// The first pocket's islands, clockwise.
    pub islands: Vec<Outline>,
    /// The drawing's other pockets (empty for one pocket).
    pub others: Vec<Pocket>,
    /// What reading the drawing resolved: outlines merged, notched or dropped
    /// (`crate::geom::overlap`), one sentence each.
    pub notes: Vec<String>,
}

impl Loops {
    /// One pocket.
    pub fn single(outer: Outline, islands: Vec<Outline>) -> Self {
        Loops {
            outer,
            islands,
            others: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Every pocket, in the listed order (1-based indices in reports and `--select`).
    pub fn pockets(&self) -> Vec<Pocket> {
        std::iter::once(Pocket {
            outer: self.outer.clone(),
            islands: self.islands.clone(),
        })
        .chain(self.others.iter().cloned())
        .collect()
    }

    /// The number of pockets.
    pub fn len(&self) -> usize {
        1 + self.others.len()
    }

    /// Never true: a drawing read has at least one pocket.
    pub fn is_empty(&self) -> bool {
        false
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Doc {
    #[serde(default)]
    units: Option<String>,
    outline: Vec<Vec<f64>>,
    #[serde(default)]
    islands: Vec<Vec<Vec<f64>>>,
}

fn vertices(raw: &[Vec<f64>], scale: f64, origin: &str) -> Result<Vec<(Point, f64)>, InputError> {
    raw.iter()
        .enumerate()
        .map(|(i, v)| match v.as_slice() {
            [x, y] => Ok((Point::new(x * scale, y * scale), 0.0)),
            [x, y, b] => Ok((Point::new(x * scale, y * scale), *b)),
            _ => Err(InputError::new("vertex", format!("{v:?}"))
                .at(format!("{origin}, vertex {i}"))
                .expected("[x, y] or [x, y, bulge]")),
        })
        .collect()
}

/// Parses the JSON schema above; `origin` names the file.
pub fn parse(text: &str, origin: &str) -> Result<Loops, InputError> {
    let doc: Doc = serde_json::from_str(text).map_err(|e| {
        InputError::new("outline JSON", e.to_string())
            .at(origin)
            .expected(r#"{"outline": [[x, y(, bulge)], ...], "islands": [[...], ...]}"#)
    })?;
    let scale = match doc.units.as_deref() {
        None | Some("mm") => 1.0,
        Some("in") => 25.4,
        Some(u) => {
            return Err(InputError::new("units", u)
                .at(origin)
                .expected("\"mm\" or \"in\""));
        }
    };
    let outer = Outline::new(
        &vertices(&doc.outline, scale, &format!("{origin}, outline"))?,
        &format!("{origin}, outline"),
    )?;
    let mut islands = Vec::new();
    for (k, isl) in doc.islands.iter().enumerate() {
        let o = format!("{origin}, island {k}");
        islands.push(Outline::new(&vertices(isl, scale, &o)?, &o)?);
    }
    check_islands(outer, islands, origin)
}

/// Normalises windings and checks that every island lies strictly inside the outer outline
/// without touching it or another island (`crate::geom::region::validate_islands`).
pub fn check_islands(
    outer: Outline,
    islands: Vec<Outline>,
    origin: &str,
) -> Result<Loops, InputError> {
    let (outer, islands) = crate::geom::region::validate_islands(outer, islands, origin)?;
    Ok(Loops::single(outer, islands))
}

/// From a set of closed loops: every pocket and its islands, nested by containment
/// ([`nesting::nest`]: even depth a pocket boundary, odd depth an island; touching or
/// crossing loops refused, naming both and where they meet).
pub fn classify(loops: Vec<Outline>, origin: &str) -> Result<Loops, InputError> {
    let (pockets, notes) = nesting::nest_noted(loops, origin)?;
    let mut pockets = pockets.into_iter();
    let Some(first) = pockets.next() else {
        return Err(InputError::new("closed outlines", 0)
            .at(origin)
            .expected("at least one closed outline"));
    };
    Ok(Loops {
        outer: first.outer,
        islands: first.islands,
        others: pockets.collect(),
        notes,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Winding;

    #[test]
    fn parses_outline_with_bulges_and_islands() {
        let text = r#"{"outline": [[0,0],[10,0],[10,10],[0,10]],
                       "islands": [[[4,4],[4,6],[6,6],[6,4]]]}"#;
        let l = parse(text, "t.json").unwrap();
        assert_eq!(l.outer.winding(), Winding::CounterClockwise);
        assert_eq!(l.islands[0].winding(), Winding::Clockwise);
        let circle = r#"{"outline": [[-5,0,1],[5,0,1]]}"#;
        let c = parse(circle, "c.json").unwrap();
        assert!((c.outer.signed_area() - std::f64::consts::PI * 25.0).abs() < 1e-9);
    }

    #[test]
    fn rejects_touching_islands_and_bad_vertices() {
        let touching = r#"{"outline": [[0,0],[10,0],[10,10],[0,10]],
                           "islands": [[[0,4],[4,4],[4,6],[0,6]]]}"#;
        let e = parse(touching, "t.json").unwrap_err().to_string();
        assert!(e.contains("island 0"), "{e}");
        let bad = r#"{"outline": [[0,0],[10],[10,10]]}"#;
        let e = parse(bad, "b.json").unwrap_err().to_string();
        assert!(e.contains("vertex 1"), "{e}");
        let bow = r#"{"outline": [[0,0],[10,10],[10,0],[0,10]]}"#;
        assert!(
            parse(bow, "bow.json")
                .unwrap_err()
                .to_string()
                .contains("self-intersecting")
        );
    }
}
