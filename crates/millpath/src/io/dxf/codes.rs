//! DXF group codes and values, from ASCII or binary DXF.
//!
//! ASCII DXF is a sequence of line pairs: an integer group code, then its value. Binary DXF
//! starts with the sentinel `AutoCAD Binary DXF\r\n\x1a\0`; each group code is a 2-byte
//! little-endian integer (R13 and later; R12 writes 1 byte, 255 escaping a 2-byte code) and
//! the value's type follows from the code's range (DXF reference, "Group Code Value Types"):
//! strings are NUL-terminated, reals 8-byte IEEE doubles, integers 2, 4 or 8 bytes, booleans 1
//! byte, binary chunks (310–319, 1004) a length byte and the data. Values are kept as text
//! here (reals written with Rust's shortest round-trip form, so nothing is lost).

use crate::error::InputError;
use crate::geom::Point;

/// One group: code and value.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// The group code.
    pub code: i32,
    /// The value, as text.
    pub value: String,
}

impl Group {
    /// The value as a real (0 when it is not a number; a malformed number is not worth
    /// refusing a whole drawing for, and the geometry checks catch what matters).
    pub fn real(&self) -> f64 {
        self.value.trim().parse().unwrap_or(0.0)
    }

    /// The value as an integer.
    pub fn int(&self) -> i64 {
        let v = self.value.trim();
        v.parse()
            .ok()
            .or_else(|| v.parse::<f64>().ok().map(|f| f as i64))
            .unwrap_or(0)
    }
}

const SENTINEL: &[u8] = b"AutoCAD Binary DXF\r\n\x1a\0";

/// The groups of a DXF file; `origin` names it.
pub fn read(bytes: &[u8], origin: &str) -> Result<Vec<Group>, InputError> {
    if let Some(rest) = bytes.strip_prefix(SENTINEL) {
        return binary(rest, origin);
    }
    // R2007 and later write UTF-8; older files their ANSI code page (usually 1252, read here
    // as Latin-1) with `\U+XXXX` escapes for other characters.
    let text: String = match std::str::from_utf8(bytes) {
        Ok(t) => t.to_owned(),
        Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
    };
    let mut lines = text.lines();
    let mut out = Vec::new();
    let mut n = 0usize;
    while let Some(code) = lines.next() {
        n += 1;
        let code = code.trim();
        if code.is_empty() && out.is_empty() {
            continue;
        }
        let Some(value) = lines.next() else { break };
        n += 1;
        let code: i32 = code.parse().map_err(|_| {
            InputError::new("DXF group code", format!("{code:?}"))
                .at(format!("{origin}, line {}", n - 1))
                .expected("an integer group code (is this a DXF file?)")
        })?;
        out.push(Group {
            code,
            value: unescape(value.trim()),
        });
    }
    if out.is_empty() {
        return Err(InputError::new("DXF", "no group codes")
            .at(origin)
            .expected("a DXF drawing"));
    }
    Ok(out)
}

/// `\U+039B` escapes replaced by their characters.
fn unescape(v: &str) -> String {
    if !v.contains("\\U+") {
        return v.to_owned();
    }
    let mut out = String::with_capacity(v.len());
    let mut rest = v;
    while let Some(i) = rest.find("\\U+") {
        out.push_str(&rest[..i]);
        let hex = rest.get(i + 3..i + 7);
        match hex
            .and_then(|h| u32::from_str_radix(h, 16).ok())
            .and_then(char::from_u32)
        {
            Some(c) => {
                out.push(c);
                rest = &rest[i + 7..];
            }
            None => {
                out.push_str("\\U+");
                rest = &rest[i + 3..];
            }
        }
    }
    out.push_str(rest);
    out
}

fn binary(b: &[u8], origin: &str) -> Result<Vec<Group>, InputError> {
    // R13+ writes 2-byte codes: the first group (0, "SECTION") starts with two zero bytes.
    let wide = b.len() >= 2 && b[0] == 0 && b[1] == 0;
    let mut i = 0usize;
    let mut out = Vec::new();
    let bad = |i: usize| {
        InputError::new(
            "binary DXF",
            format!("truncated at byte {}", i + SENTINEL.len()),
        )
        .at(origin)
        .expected("a complete binary DXF file")
    };
    let take = |i: &mut usize, n: usize| -> Result<&[u8], InputError> {
        let s = b.get(*i..*i + n).ok_or_else(|| bad(*i))?;
        *i += n;
        Ok(s)
    };
    while i < b.len() {
        let code = if wide {
            let c = take(&mut i, 2)?;
            i32::from(i16::from_le_bytes([c[0], c[1]]))
        } else {
            let c = take(&mut i, 1)?[0];
            if c == 255 {
                let c = take(&mut i, 2)?;
                i32::from(i16::from_le_bytes([c[0], c[1]]))
            } else {
                i32::from(c)
            }
        };
        let value = match code {
            10..=59 | 110..=149 | 210..=239 | 460..=469 | 1010..=1059 => {
                let v = take(&mut i, 8)?;
                let mut a = [0u8; 8];
                a.copy_from_slice(v);
                f64::from_le_bytes(a).to_string()
            }
            60..=79 | 170..=179 | 270..=289 | 370..=389 | 400..=409 | 1060..=1070 => {
                let v = take(&mut i, 2)?;
                i16::from_le_bytes([v[0], v[1]]).to_string()
            }
            90..=99 | 420..=429 | 440..=459 | 1071 => {
                let v = take(&mut i, 4)?;
                i32::from_le_bytes([v[0], v[1], v[2], v[3]]).to_string()
            }
            160..=169 => {
                let v = take(&mut i, 8)?;
                let mut a = [0u8; 8];
                a.copy_from_slice(v);
                i64::from_le_bytes(a).to_string()
            }
            290..=299 => take(&mut i, 1)?[0].to_string(),
            310..=319 | 1004 => {
                let n = take(&mut i, 1)?[0] as usize;
                take(&mut i, n)?;
                String::new()
            }
            _ => {
                let end = b[i..].iter().position(|&c| c == 0).ok_or_else(|| bad(i))?;
                let s = String::from_utf8_lossy(&b[i..i + end]).into_owned();
                i += end + 1;
                s
            }
        };
        let eof = code == 0 && value == "EOF";
        out.push(Group { code, value });
        if eof {
            break;
        }
    }
    Ok(out)
}

/// One entity: its type name and its groups (the leading `0` group excluded).
#[derive(Debug, Clone)]
pub struct Record {
    /// The entity type (`LINE`, `ARC`, …).
    pub kind: String,
    /// Its groups.
    pub groups: Vec<Group>,
}

impl Record {
    pub(super) fn first(&self, code: i32) -> Option<&Group> {
        self.groups.iter().find(|g| g.code == code)
    }
    pub(super) fn real(&self, code: i32, default: f64) -> f64 {
        self.first(code).map_or(default, Group::real)
    }
    pub(super) fn int(&self, code: i32, default: i64) -> i64 {
        self.first(code).map_or(default, Group::int)
    }
    pub(super) fn text(&self, code: i32) -> &str {
        self.first(code).map_or("", |g| g.value.as_str())
    }
    pub(super) fn point(&self, xc: i32) -> Point {
        Point::new(self.real(xc, 0.0), self.real(xc + 10, 0.0))
    }
    /// `Some(mirror)` for a plan-view extrusion (mirror when it points down), `None` for a
    /// tilted one.
    pub(super) fn extrusion(&self) -> Option<bool> {
        let (x, y, z) = (
            self.real(210, 0.0),
            self.real(220, 0.0),
            self.real(230, 1.0),
        );
        let n = (x * x + y * y + z * z).sqrt();
        if n == 0.0 || (x.abs() + y.abs()) > 1e-9 * n {
            None
        } else {
            Some(z < 0.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_pairs_and_binary_values() {
        let g = read(b"  0\r\nSECTION\r\n  2\r\nENTITIES\r\n 10\r\n1.5\r\n", "t").unwrap();
        assert_eq!(g.len(), 3);
        assert_eq!((g[2].code, g[2].real()), (10, 1.5));
        let mut bin = SENTINEL.to_vec();
        bin.extend([0, 0]);
        bin.extend(b"SECTION\0");
        bin.extend([10, 0]);
        bin.extend(2.25f64.to_le_bytes());
        bin.extend([70, 0]);
        bin.extend(7i16.to_le_bytes());
        let g = read(&bin, "t").unwrap();
        assert_eq!(g[0].value, "SECTION");
        assert_eq!((g[1].code, g[1].real()), (10, 2.25));
        assert_eq!((g[2].code, g[2].int()), (70, 7));
        let e = read(&bin[..bin.len() - 1], "t.dxf")
            .unwrap_err()
            .to_string();
        assert!(e.contains("truncated") && e.contains("t.dxf"), "{e}");
        let g = read(b"8\n\\U+039B\\U+0391x\xe4\n", "t").unwrap();
        assert_eq!(g[0].value, "ΛΑxä");
        let e = read(b"hello\nworld\n", "x.dxf").unwrap_err().to_string();
        assert!(e.contains("group code") && e.contains("line 1"), "{e}");
    }
}
