//! Point-list input for the free-form contour: CSV or JSON.
//!
//! # CSV
//! One point per line, `x,y` (mm). Groups of points (for the four-point curve) are separated
//! either by a blank line or by a third `group` column (a new group starts whenever its value
//! changes). A first line whose fields are not numbers is a header (`x,y` or `x,y,group`).
//! Lines starting with `#` are comments. Separators: comma, semicolon, tab or spaces.
//!
//! # JSON
//! Either `{"groups": [[[x, y], ...], ...]}` (explicit groups) or `{"points": [[x, y], ...]}`
//! (one group; cut into groups of 4 in four-point mode by the caller's choice of curve).
//!
//! Every point keeps where it came from (`file:line` for CSV, `file: groups[g][i]` for JSON) so
//! that errors about it can name it.

use crate::curve::LabeledPoint;
use crate::error::InputError;
use crate::geom::Point;
use serde::Deserialize;

/// Parses a points file; `name` is the file name used in error origins. JSON when the first
/// non-blank character is `{`, CSV otherwise.
pub fn parse(text: &str, name: &str) -> Result<Vec<Vec<LabeledPoint>>, InputError> {
    if text.trim_start().starts_with('{') {
        parse_json(text, name)
    } else {
        parse_csv(text, name)
    }
}

fn finite(x: f64, y: f64, origin: &str) -> Result<Point, InputError> {
    if x.is_finite() && y.is_finite() {
        Ok(Point::new(x, y))
    } else {
        Err(InputError::new("point", format!("({x}, {y})"))
            .at(origin)
            .expected("finite coordinates in mm"))
    }
}

/// Parses CSV (see the module docs).
pub fn parse_csv(text: &str, name: &str) -> Result<Vec<Vec<LabeledPoint>>, InputError> {
    let mut groups: Vec<Vec<LabeledPoint>> = vec![Vec::new()];
    let mut last_group: Option<String> = None;
    let mut seen_data = false;
    for (i, raw) in text.lines().enumerate() {
        let origin = format!("{name}:{}", i + 1);
        let line = raw.trim();
        if line.starts_with('#') {
            continue;
        }
        if line.is_empty() {
            if groups.last().is_some_and(|g| !g.is_empty()) {
                groups.push(Vec::new());
            }
            continue;
        }
        let fields: Vec<&str> = line
            .split([',', ';', '\t', ' '])
            .filter(|f| !f.is_empty())
            .collect();
        let nums: Vec<Option<f64>> = fields
            .iter()
            .take(2)
            .map(|f| f.parse::<f64>().ok())
            .collect();
        if !seen_data && nums.iter().all(Option::is_none) {
            continue; // header
        }
        seen_data = true;
        let (x, y) = match (fields.len(), nums.as_slice()) {
            (2 | 3, [Some(x), Some(y)]) => (*x, *y),
            _ => {
                return Err(InputError::new("CSV line", format!("{line:?}"))
                    .at(origin)
                    .expected("`x,y` or `x,y,group` with numbers in mm"));
            }
        };
        let p = finite(x, y, &origin)?;
        if let Some(g) = fields.get(2) {
            if last_group.as_deref().is_some_and(|l| l != *g)
                && groups.last().is_some_and(|g| !g.is_empty())
            {
                groups.push(Vec::new());
            }
            last_group = Some((*g).to_owned());
        }
        if let Some(g) = groups.last_mut() {
            g.push(LabeledPoint { p, origin });
        }
    }
    groups.retain(|g| !g.is_empty());
    if groups.is_empty() {
        return Err(InputError::new("points file", name).expected("at least 4 points `x,y`"));
    }
    Ok(groups)
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonPoints {
    groups: Option<Vec<Vec<[f64; 2]>>>,
    points: Option<Vec<[f64; 2]>>,
}

/// Parses JSON (see the module docs).
pub fn parse_json(text: &str, name: &str) -> Result<Vec<Vec<LabeledPoint>>, InputError> {
    let j: JsonPoints = serde_json::from_str(text).map_err(|e| {
        InputError::new("JSON points file", name)
            .at(format!("{name}:{}:{}", e.line(), e.column()))
            .expected(format!(
                r#"{{"groups": [[[x, y], ...], ...]}} or {{"points": [[x, y], ...]}} ({e})"#
            ))
    })?;
    let (groups, key) = match (j.groups, j.points) {
        (Some(g), None) => (g, "groups"),
        (None, Some(p)) => (vec![p], "points"),
        _ => {
            return Err(InputError::new("JSON points file", name)
                .expected(r#"exactly one of "groups" or "points""#));
        }
    };
    groups
        .iter()
        .enumerate()
        .map(|(gi, g)| {
            g.iter()
                .enumerate()
                .map(|(i, [x, y])| {
                    let origin = if key == "groups" {
                        format!("{name}: groups[{gi}][{i}]")
                    } else {
                        format!("{name}: points[{i}]")
                    };
                    Ok(LabeledPoint {
                        p: finite(*x, *y, &origin)?,
                        origin,
                    })
                })
                .collect()
        })
        .collect()
}

/// The four-point groups of a flat point list: consecutive groups of 4 sharing their end
/// points (`P1..P4, P4..P7, ...`), which is how a single list of `3k + 1` points (or `3k` for
/// a closed list) is read in four-point mode. Returned unchanged if it already has groups.
pub fn regroup_for_four_point(groups: Vec<Vec<LabeledPoint>>) -> Vec<Vec<LabeledPoint>> {
    if groups.len() != 1 {
        return groups;
    }
    let pts = &groups[0];
    if pts.len() <= 4 {
        return groups;
    }
    let mut out = Vec::new();
    let mut i = 0;
    while i + 3 < pts.len() {
        out.push(pts[i..i + 4].to_vec());
        i += 3;
    }
    if i + 1 < pts.len() {
        // Leftover points: a short group, reported by the curve builder with its origin.
        out.push(pts[i..].to_vec());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_groups_by_blank_line_and_column() {
        let g = parse(
            "x,y\n1,15\n3,14\n5,12.5\n7,10\n\n15,8\n11,17\n5,16.5\n1,15\n",
            "a.csv",
        )
        .unwrap();
        assert_eq!(g.len(), 2);
        assert_eq!(g[1][0].origin, "a.csv:7");
        let g = parse(
            "1,15,a\n3,14,a\n5,12.5,a\n7,10,a\n15,8,b\n11,17,b\n",
            "b.csv",
        )
        .unwrap();
        assert_eq!((g.len(), g[0].len(), g[1].len()), (2, 4, 2));
    }

    #[test]
    fn csv_errors_name_the_line() {
        let e = parse("1,2\n3,nan\n", "c.csv").unwrap_err().to_string();
        assert!(e.contains("c.csv:2"), "{e}");
        let e = parse("1,2\n3;x\n", "c.csv").unwrap_err().to_string();
        assert!(e.contains("c.csv:2"), "{e}");
    }

    #[test]
    fn json_both_schemas() {
        let g = parse(r#"{"groups": [[[1,15],[3,14],[5,12.5],[7,10]]]}"#, "a.json").unwrap();
        assert_eq!(g[0][3].origin, "a.json: groups[0][3]");
        let g = parse(r#"{"points": [[0,0],[1,0],[1,1],[0,1]]}"#, "b.json").unwrap();
        assert_eq!(g[0].len(), 4);
        assert!(parse(r#"{"pts": []}"#, "c.json").is_err());
    }
}
