//! A LinuxCNC tool table (`tool.tbl`): tool numbers → length offsets and diameters.
//!
//! One tool a line: `T<n> P<pocket> [X Y Z A B C U V W <offset>] [D<diameter>]
//! [I J Q <lathe>] [;comment]`, words in any order, case-insensitive (LinuxCNC's
//! `tooldata_read_entry`). The reader uses the X/Y/Z offsets (G43, G43 H), the diameter and
//! the lathe orientation Q (cutter compensation); rotary, UVW and the angles I/J are read and
//! ignored. Values are in the
//! table's units (the machine's units in LinuxCNC, given here), stored in mm.
//!
//! ```text
//! T1 P1 Z0.511 D3 ;3mm end mill
//! T4 P2 Z10 D16
//! ```

use super::dialect::Units;
use crate::error::InputError;
use crate::geom::Vec3;
use std::collections::BTreeMap;

/// One tool of the table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToolEntry {
    /// The length offsets X, Y, Z (mm).
    pub offset: Vec3,
    /// The diameter (mm).
    pub diameter: f64,
    /// The lathe tool orientation `Q` (0 for a mill tool, 1–9 for lathe tools).
    pub orientation: u8,
}

/// A tool table.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ToolTable {
    tools: BTreeMap<u32, ToolEntry>,
}

impl ToolTable {
    /// Parses a table; `units` are the units its numbers are in; `origin` names it in
    /// messages.
    pub fn parse(text: &str, units: Units, origin: &str) -> Result<Self, InputError> {
        let k = units.mm_per_unit();
        let mut tools = BTreeMap::new();
        for (i, raw) in text.lines().enumerate() {
            let line = raw.split(';').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let at = || format!("{origin}:{}", i + 1);
            let mut number = None;
            let mut entry = ToolEntry {
                offset: Vec3::ZERO,
                diameter: 0.0,
                orientation: 0,
            };
            for word in line.split_whitespace() {
                let mut chars = word.chars();
                let letter = chars.next().unwrap_or(' ').to_ascii_uppercase();
                let value: f64 = chars
                    .as_str()
                    .parse()
                    .ok()
                    .filter(|v: &f64| v.is_finite())
                    .ok_or_else(|| {
                        InputError::new("tool table word", word)
                            .at(at())
                            .expected("a letter (T P X Y Z A B C U V W D I J Q) and a number")
                    })?;
                match letter {
                    'T' => {
                        if value < 0.0 || value.fract() != 0.0 || value > f64::from(u32::MAX) {
                            return Err(InputError::new("tool number", word)
                                .at(at())
                                .expected("T and an integer >= 0"));
                        }
                        number = Some(value as u32);
                    }
                    'X' => entry.offset.x = value * k,
                    'Y' => entry.offset.y = value * k,
                    'Z' => entry.offset.z = value * k,
                    'D' => entry.diameter = value * k,
                    'Q' => {
                        if !(0.0..=9.0).contains(&value) || value.fract() != 0.0 {
                            return Err(InputError::new("tool orientation", word)
                                .at(at())
                                .expected("Q and an integer 0..9"));
                        }
                        entry.orientation = value as u8;
                    }
                    'P' | 'A' | 'B' | 'C' | 'U' | 'V' | 'W' | 'I' | 'J' => {}
                    _ => {
                        return Err(InputError::new("tool table word", word)
                            .at(at())
                            .expected("T P X Y Z A B C U V W D I J Q"));
                    }
                }
            }
            let Some(n) = number else {
                return Err(InputError::new("tool table line", raw.trim())
                    .at(at())
                    .expected("a T word (tool number)"));
            };
            tools.insert(n, entry);
        }
        Ok(ToolTable { tools })
    }

    /// Reads a table file.
    pub fn read(path: &std::path::Path, units: Units) -> Result<Self, InputError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            InputError::new("tool table", path.display())
                .expected(format!("a readable LinuxCNC tool table ({e})"))
        })?;
        Self::parse(&text, units, &path.display().to_string())
    }

    /// Tool `n` (tool 0, the empty spindle, has no offsets).
    pub fn get(&self, n: u32) -> Option<ToolEntry> {
        if n == 0 {
            return Some(self.tools.get(&0).copied().unwrap_or(ToolEntry {
                offset: Vec3::ZERO,
                diameter: 0.0,
                orientation: 0,
            }));
        }
        self.tools.get(&n).copied()
    }

    /// Number of tools.
    pub fn len(&self) -> usize {
        self.tools.len()
    }

    /// Whether the table has no tools.
    pub fn is_empty(&self) -> bool {
        self.tools.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_linuxcnc_lines() {
        let t = ToolTable::parse(
            "T1 P1 Z0.511 D3 ;3mm end mill\n\nt4 p2 z10 d16 x-1\n; only a comment\n",
            Units::Mm,
            "tool.tbl",
        )
        .unwrap();
        assert_eq!(t.len(), 2);
        assert_eq!(t.get(1).unwrap().offset, Vec3::new(0.0, 0.0, 0.511));
        assert!((t.get(4).unwrap().diameter - 16.0).abs() < 1e-12);
        assert!((t.get(4).unwrap().offset.x + 1.0).abs() < 1e-12);
        assert!(t.get(2).is_none());
        let inch = ToolTable::parse("T2 Z1", Units::Inch, "t").unwrap();
        assert!((inch.get(2).unwrap().offset.z - 25.4).abs() < 1e-12);
        let lathe = ToolTable::parse("T2 P2 D0.1 I+85 J+25 Q2 ;", Units::Inch, "t").unwrap();
        assert_eq!(lathe.get(2).unwrap().orientation, 2);
        assert!((lathe.get(2).unwrap().diameter - 2.54).abs() < 1e-12);
        for bad in ["T1 Zx", "P1 Z1", "T1.5 Z1", "T1 K2", "T1 Q10", "T1 Q1.5"] {
            let e = ToolTable::parse(bad, Units::Mm, "t.tbl").unwrap_err();
            assert!(e.to_string().contains("t.tbl:1"), "{bad}: {e}");
        }
    }
}
