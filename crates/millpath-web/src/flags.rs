//! The page's options → the engine's pocket settings. The page sends one JSON object whose
//! keys are `millpath pocket`'s flags without the dashes (`"tool-diameter"`, `"dialect"`) and
//! whose values are what the flag would take: a number or its text (`12.7`, `"12.7"`), a text
//! (`"600ipm"`), `true`/`false` for a switch. A key not given keeps the flag's default, so
//! the same object written as flags (`--tool-diameter 12.7 …`) runs the same job in the CLI.
//! Every refusal is an `InputError` naming the flag, as the CLI's are.
//!
//! ```text
//! {"strategy": "spiral", "tool-diameter": 6, "depth": "5", "dialect": "fanuc"}
//!   ≡ millpath pocket FILE --strategy spiral --tool-diameter 6 --depth 5 --dialect fanuc
//! ```

use millpath::job::{PocketSettings, ProgramSettings};
use millpath::{Error, InputError};
use serde_json::{Map, Value};

/// The settings one options object gives.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The pocket job's settings (with the drawing's import settings).
    pub pocket: PocketSettings,
    /// How the program is written.
    pub program: ProgramSettings,
    /// `--select`: the pockets cut, by index (all when `None`).
    pub select: Option<String>,
}

/// The flags the page may set (`--bottom-outline`, `--rest-from` name other files, which a
/// page has no access to, and `--list`, `--json`, `-o`, `--report`, `--html` are outputs the
/// page always has).
pub const FLAGS: &[&str] = &[
    "strategy",
    "tool-diameter",
    "flute-length",
    "stepover",
    "depth",
    "step-down",
    "wall-stock",
    "floor-stock",
    "conventional",
    "entry",
    "helix-radius",
    "ramp-angle",
    "safe-height",
    "clearance-height",
    "feed",
    "slowdown",
    "angle",
    "transition",
    "min-radius",
    "morph",
    "arcs",
    "both-ways",
    "lift",
    "finish",
    "no-feed-modulation",
    "machine",
    "cell",
    "draft",
    "tolerance",
    "select",
    "layer",
    "join-tolerance",
    "drawing-units",
    "dialect",
    "units",
    "decimals",
    "tool-number",
    "spindle",
    "coolant",
    "line-numbers",
];

/// Reads an options object (JSON text, see the module docs).
pub fn parse(json: &str) -> Result<Settings, Error> {
    let value: Value = serde_json::from_str(json).map_err(|e| {
        InputError::new("options", json.chars().take(80).collect::<String>())
            .at("the page")
            .expected(format!("a JSON object of flags ({e})"))
    })?;
    let Value::Object(map) = value else {
        return Err(InputError::new("options", value)
            .at("the page")
            .expected("a JSON object of flags")
            .into());
    };
    if let Some(k) = map.keys().find(|k| !FLAGS.contains(&k.as_str())) {
        return Err(InputError::new("flag", format!("--{k}"))
            .at("the page's options")
            .expected(format!("one of --{}", FLAGS.join(", --")))
            .into());
    }
    let f = Flags(map);
    let mut s = PocketSettings::default();
    f.text("strategy", &mut s.strategy)?;
    f.f64("tool-diameter", &mut s.tool_diameter)?;
    f.opt_f64("flute-length", &mut s.flute_length)?;
    s.apply_strategy_defaults();
    f.text("stepover", &mut s.stepover)?;
    f.f64("depth", &mut s.depth)?;
    f.f64("step-down", &mut s.step_down)?;
    f.f64("wall-stock", &mut s.wall_stock)?;
    f.f64("floor-stock", &mut s.floor_stock)?;
    f.bool("conventional", &mut s.conventional)?;
    f.text("entry", &mut s.entry)?;
    f.opt_f64("helix-radius", &mut s.helix_radius)?;
    f.f64("ramp-angle", &mut s.ramp_angle)?;
    f.f64("safe-height", &mut s.safe_height)?;
    f.f64("clearance-height", &mut s.clearance_height)?;
    f.text("feed", &mut s.feed)?;
    f.f64("slowdown", &mut s.slowdown)?;
    f.f64("angle", &mut s.angle)?;
    f.opt_f64("transition", &mut s.transition)?;
    f.f64("min-radius", &mut s.min_radius)?;
    f.opt_text("morph", &mut s.morph)?;
    f.bool("arcs", &mut s.arcs)?;
    f.bool("both-ways", &mut s.both_ways)?;
    f.f64("lift", &mut s.lift)?;
    f.bool("finish", &mut s.finish)?;
    f.bool("no-feed-modulation", &mut s.no_feed_modulation)?;
    f.text("machine", &mut s.machine)?;
    f.opt_f64("cell", &mut s.cell)?;
    f.opt_f64("draft", &mut s.draft)?;
    f.opt_f64("tolerance", &mut s.tolerance)?;
    f.opt_text("layer", &mut s.import.layer)?;
    f.f64("join-tolerance", &mut s.import.join_tolerance)?;
    f.opt_text("drawing-units", &mut s.import.drawing_units)?;
    let mut p = ProgramSettings::default();
    if let Some(t) = f.get_text("dialect")? {
        p.dialect = t.parse().map_err(|e: InputError| e.at("--dialect"))?;
    }
    if let Some(t) = f.get_text("units")? {
        p.units = t.parse().map_err(|e: InputError| e.at("--units"))?;
    }
    if let Some(t) = f.get_text("coolant")? {
        p.coolant = t.parse().map_err(|e: InputError| e.at("--coolant"))?;
    }
    if let Some(n) = f.get_count("decimals")? {
        p.decimals = Some(n);
    }
    if let Some(n) = f.get_count("tool-number")? {
        p.tool_number = n;
    }
    f.f64("spindle", &mut p.spindle)?;
    f.bool("line-numbers", &mut p.line_numbers)?;
    let mut select = None;
    f.opt_text("select", &mut select)?;
    Ok(Settings {
        pocket: s,
        program: p,
        select,
    })
}

/// The options object's values by flag.
struct Flags(Map<String, Value>);

/// The refusal of `value` given for `--flag`, expecting `what`.
fn bad(flag: &str, value: &Value, what: &str) -> InputError {
    InputError::new(flag.replace('-', " "), value)
        .at(format!("--{flag}"))
        .expected(what.to_owned())
}

impl Flags {
    /// A text flag's value: a string, or a number's text; `None` when not given (or null).
    fn get_text(&self, flag: &str) -> Result<Option<String>, InputError> {
        match self.0.get(flag) {
            None | Some(Value::Null) => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(Value::Number(n)) => Ok(Some(n.to_string())),
            Some(v) => Err(bad(flag, v, "a text or a number")),
        }
    }

    /// A number flag's value: a JSON number or a text that reads as one.
    fn get_f64(&self, flag: &str) -> Result<Option<f64>, InputError> {
        match self.0.get(flag) {
            None | Some(Value::Null) => Ok(None),
            Some(v @ Value::Number(n)) => {
                n.as_f64().map(Some).ok_or_else(|| bad(flag, v, "a number"))
            }
            Some(v @ Value::String(s)) => s
                .trim()
                .parse::<f64>()
                .map(Some)
                .map_err(|_| bad(flag, v, "a number")),
            Some(v) => Err(bad(flag, v, "a number")),
        }
    }

    /// A count flag's value: a whole number ≥ 0 (as a number or a text).
    fn get_count(&self, flag: &str) -> Result<Option<u32>, InputError> {
        let Some(x) = self.get_f64(flag)? else {
            return Ok(None);
        };
        let whole = x.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&x);
        if !whole {
            return Err(bad(flag, &Value::from(x), "a whole number ≥ 0"));
        }
        // Exact: x is a whole number within u32's range.
        Ok(Some(x as u32))
    }

    fn text(&self, flag: &str, into: &mut String) -> Result<(), InputError> {
        if let Some(t) = self.get_text(flag)? {
            *into = t;
        }
        Ok(())
    }

    fn opt_text(&self, flag: &str, into: &mut Option<String>) -> Result<(), InputError> {
        if let Some(t) = self.get_text(flag)? {
            *into = Some(t);
        }
        Ok(())
    }

    fn f64(&self, flag: &str, into: &mut f64) -> Result<(), InputError> {
        if let Some(x) = self.get_f64(flag)? {
            *into = x;
        }
        Ok(())
    }

    fn opt_f64(&self, flag: &str, into: &mut Option<f64>) -> Result<(), InputError> {
        if let Some(x) = self.get_f64(flag)? {
            *into = Some(x);
        }
        Ok(())
    }

    /// A switch: `true` sets it, `false` (or not given) leaves the default (off).
    fn bool(&self, flag: &str, into: &mut bool) -> Result<(), InputError> {
        match self.0.get(flag) {
            None | Some(Value::Null) => Ok(()),
            Some(Value::Bool(b)) => {
                *into = *b;
                Ok(())
            }
            Some(v) => Err(bad(flag, v, "true or false (a switch)")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An empty object is the CLI's defaults; given flags land in their fields.
    #[test]
    fn flags_land_where_the_cli_puts_them() {
        let d = parse("{}").unwrap();
        assert_eq!(d.pocket, PocketSettings::default());
        assert_eq!(d.program, ProgramSettings::default());
        let s = parse(
            r#"{"strategy": "zigzag", "tool-diameter": "6", "depth": 5, "arcs": true,
                "dialect": "fanuc", "tool-number": 3, "select": "1,2", "layer": "CUT"}"#,
        )
        .unwrap();
        assert_eq!(s.pocket.strategy, "zigzag");
        assert!((s.pocket.tool_diameter - 6.0).abs() < 1e-12);
        assert!((s.pocket.depth - 5.0).abs() < 1e-12);
        assert!(s.pocket.arcs);
        assert_eq!(s.program.dialect, millpath::gcode::Dialect::Fanuc);
        assert_eq!(s.program.tool_number, 3);
        assert_eq!(s.select.as_deref(), Some("1,2"));
        assert_eq!(s.pocket.import.layer.as_deref(), Some("CUT"));
    }

    /// Refusals name the flag, the value and what is accepted.
    #[test]
    fn adaptive_takes_its_own_defaults_as_the_cli_does() {
        let s = parse(r#"{"strategy": "adaptive", "tool-diameter": 6}"#).unwrap();
        assert_eq!(s.pocket.stepover, "0.1");
        assert!((s.pocket.step_down - 18.0).abs() < 1e-12);
        let s =
            parse(r#"{"strategy": "adaptive", "flute-length": 10, "stepover": "0.2"}"#).unwrap();
        assert_eq!(s.pocket.stepover, "0.2");
        assert!((s.pocket.step_down - 10.0).abs() < 1e-12);
        let s = parse(r#"{"strategy": "adaptive", "step-down": 4}"#).unwrap();
        assert!((s.pocket.step_down - 4.0).abs() < 1e-12);
    }

    #[test]
    fn refusals_name_the_flag() {
        let msg = |j: &str| parse(j).unwrap_err().to_string();
        assert_eq!(
            msg(r#"{"depth": "deep"}"#),
            "invalid depth = \"deep\" (from --depth): expected a number"
        );
        assert!(msg(r#"{"rest-from": "a.ngc"}"#).contains("--rest-from"));
        assert!(msg(r#"{"dialect": "heidenhain"}"#).contains("(from --dialect)"));
        assert!(msg(r#"{"tool-number": 1.5}"#).contains("a whole number"));
        assert!(msg(r#"{"arcs": "yes"}"#).contains("a switch"));
        assert!(msg("[1]").contains("a JSON object of flags"));
    }
}
