//! millpath in the browser: the engine's `pocket` job for a web page, compiled to
//! `wasm32-unknown-unknown` and bound with wasm-bindgen. Thin, like the CLI and the Python
//! package: a drawing's bytes (or a built-in sample's name) and the options as the CLI's flags
//! in ([`flags`]); the program, the report, the preview and the HTML report out, each exactly
//! what `millpath pocket` writes with `-o`, `--report` and `--html`; a refusal as the text the
//! CLI prints after `error: `. Nothing here plans, checks or formats anything itself.
//!
//! ```text
//! const run = pocket(bytes, "part.dxf", '{"strategy": "auto", "depth": 5}');  // throws Error(message)
//! run.gcode()   // Uint8Array: the bytes of `millpath pocket part.dxf --strategy auto --depth 5 -o …`
//! run.report()  // the JSON of `--report`
//! run.free()
//! ```
//!
//! The same crate builds on the host (its options are tested there); calling the exported
//! functions needs a JavaScript host.

pub mod flags;

use millpath::Error;
use millpath::job::PocketRun;
use wasm_bindgen::prelude::*;

#[wasm_bindgen]
extern "C" {
    /// `console.error`, where a panic's message goes before the module traps.
    #[wasm_bindgen(js_namespace = console, js_name = error)]
    fn console_error(message: &str);
}

/// Sends a panic's message to the console (a panic is a bug: the page reports an internal
/// error and loads the module anew). Call once after the module is loaded.
#[wasm_bindgen]
pub fn install_panic_hook() {
    std::panic::set_hook(Box::new(|info| {
        console_error(&format!("internal error: millpath panicked: {info}"));
    }));
}

/// The engine's version.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_owned()
}

/// The machine presets `machine` takes (`--machine`).
#[wasm_bindgen]
pub fn machines() -> Vec<String> {
    millpath::machine::Machine::PRESET_NAMES
        .iter()
        .map(|s| (*s).to_owned())
        .collect()
}

/// The built-in samples a drawing may be named instead of given.
#[wasm_bindgen]
pub fn samples() -> Vec<String> {
    millpath::job::SAMPLE_OUTLINES
        .iter()
        .map(|s| (*s).to_owned())
        .collect()
}

/// A planned pocket job: the program and its reports.
#[wasm_bindgen]
#[derive(Debug)]
pub struct Planned {
    run: PocketRun,
    outline: String,
    notes: Vec<String>,
    pockets: Vec<String>,
}

#[wasm_bindgen]
impl Planned {
    /// The program's bytes (`-o`).
    pub fn gcode(&self) -> Vec<u8> {
        self.run.gcode.clone()
    }

    /// The report as `--report` writes it (pretty JSON).
    pub fn report(&self) -> Result<String, JsError> {
        serde_json::to_string_pretty(&self.run.report)
            .map_err(|e| js(&Error::internal(format!("report serialisation: {e}"))))
    }

    /// The notes the CLI prints on standard error (`note: ` left off): what the drawing held,
    /// what the planner did of note.
    pub fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    /// The drawing's pockets, one line each, as `--list` prints them.
    pub fn pockets(&self) -> Vec<String> {
        self.pockets.clone()
    }

    /// The toolpath over the pockets as one SVG picture, coloured by the feed the machine
    /// reaches, with the side view under it (the `--html` report's preview, and its levels).
    pub fn preview(&self) -> Result<String, JsError> {
        let plan = self.run.plan().map_err(|e| js(&e))?;
        let opts = millpath::report::PreviewOptions::default()
            .with_title(Some(format!(
                "millpath pocket {} {}",
                self.outline, self.run.name
            )))
            .with_achieved_feed(Some(
                plan.peak_feed_by_move(self.run.part.toolpath.moves.len()),
            ))
            .with_side_view(true);
        Ok(millpath::report::toolpath_svg(
            &self.run.part.toolpath,
            &self.run.outlines(),
            &opts,
        ))
    }

    /// The self-contained HTML report `--html` writes (summary, viewer with playback on the
    /// machine, feed plot).
    pub fn html(&self) -> Result<String, JsError> {
        Ok(self.run.html(&self.outline).map_err(|e| js(&e))?.to_html())
    }
}

/// The refusal as a JavaScript `Error` whose message is what the CLI prints after `error: `.
fn js(e: &Error) -> JsError {
    JsError::new(&e.to_string())
}

/// Plans the pockets of a drawing as `millpath pocket NAME FLAGS -o … --report …` does:
/// `drawing` is the file's bytes, `name` its name (its extension says how to read it; it
/// names the file in messages), or `drawing` is absent and `name` a built-in sample
/// (`sample:aerospace`); `options` the flags as a JSON object ([`flags`]).
#[wasm_bindgen]
#[allow(clippy::needless_pass_by_value)] // wasm-bindgen hands the bytes over owned
pub fn pocket(drawing: Option<Vec<u8>>, name: &str, options: &str) -> Result<Planned, JsError> {
    plan(drawing.as_deref(), name, options).map_err(|e| js(&e))
}

/// The drawing's pockets, one line each, as `millpath pocket NAME --list` prints them.
#[wasm_bindgen]
#[allow(clippy::needless_pass_by_value)] // wasm-bindgen hands the bytes over owned
pub fn list(drawing: Option<Vec<u8>>, name: &str, options: &str) -> Result<Vec<String>, JsError> {
    let s = flags::parse(options).map_err(|e| js(&e))?;
    let (loops, _) = load(drawing.as_deref(), name, &s.pocket.import).map_err(|e| js(&e))?;
    Ok(millpath::job::pocket::list_lines(&loops))
}

/// The drawing's loops and notes: the bytes read by the name's extension, or the sample.
fn load(
    drawing: Option<&[u8]>,
    name: &str,
    import: &millpath::io::ImportSettings,
) -> Result<(millpath::io::outline_json::Loops, Vec<String>), Error> {
    let (loops, note) = match drawing {
        Some(bytes) => millpath::io::read_outline_bytes(name, bytes, import)?,
        None => millpath::job::load_outline(name, import)?,
    };
    let notes = note
        .into_iter()
        .chain(loops.notes.iter().map(|n| format!("{name}: {n}")))
        .collect();
    Ok((loops, notes))
}

/// The pocket job, in the CLI's order: the options, the checks made before the drawing is
/// read, the drawing, the plan.
fn plan(drawing: Option<&[u8]>, name: &str, options: &str) -> Result<Planned, Error> {
    let s = flags::parse(options)?;
    s.pocket.check_before_loading(&s.program)?;
    let (loops, mut notes) = load(drawing, name, &s.pocket.import)?;
    let pockets = millpath::job::pocket::list_lines(&loops);
    let run = millpath::job::pocket::run(
        &loops,
        name,
        &s.pocket,
        &s.program,
        s.select.as_deref(),
        &mut |n| notes.push(n),
    )?;
    notes.extend(run.report.notes.iter().cloned());
    Ok(Planned {
        run,
        outline: name.to_owned(),
        notes,
        pockets,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small drawing planned through the binding's path gives the program the job gives
    /// on the same loops, and a bad drawing the reader's refusal naming the file.
    #[test]
    fn binding_runs_the_cli_job() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="40mm" height="30mm" viewBox="0 0 40 30"><rect x="0" y="0" width="40" height="30"/></svg>"#;
        let opts = r#"{"strategy": "offset", "tool-diameter": 6, "depth": 2, "step-down": 2}"#;
        let planned = plan(Some(svg.as_bytes()), "box.svg", opts).unwrap();
        let s = flags::parse(opts).unwrap();
        let (loops, _) = millpath::io::read_outline_bytes(
            "box.svg",
            svg.as_bytes(),
            &millpath::io::ImportSettings::default(),
        )
        .unwrap();
        let direct =
            millpath::job::pocket::run(&loops, "box.svg", &s.pocket, &s.program, None, &mut |_| {})
                .unwrap();
        assert_eq!(planned.gcode(), direct.gcode);
        assert!(planned.run.report.problems.is_empty());
        assert_eq!(planned.pockets.len(), 1);
        let e = plan(Some(b"0\nSECTION\n2\nNONSENSE"), "bad.dxf", "{}").unwrap_err();
        assert!(e.to_string().contains("bad.dxf"), "{e}");
        assert_eq!(e.exit_code(), 2);
    }
}
