//! One module per subcommand, each thin over the engine.

pub mod calibrate;
pub mod contour;
pub mod demo;
pub mod drill;
pub mod estimate;
pub mod five_axis;
pub mod html;
pub mod job;
pub mod machines;
pub mod optimize;
pub mod outline_input;
pub mod output;
pub mod pocket;
pub mod profile;
pub mod sweep;
pub mod verify;

use millpath::Error;
use millpath::machine::Machine;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Prints a line on stdout (the engine never prints; the CLI does, here).
pub fn print(line: &str) {
    let _ = writeln!(std::io::stdout(), "{line}");
}

/// Prints a line on stderr.
pub fn eprint(line: &str) {
    let _ = writeln!(std::io::stderr(), "{line}");
}

/// `note: dialect linuxcnc: found from …` on stderr, when the dialect was not named.
pub fn dialect_note(choice: &millpath::gcode::DialectChoice) {
    if choice.reason != millpath::gcode::DialectReason::Named {
        eprint(&format!("note: {choice}"));
    }
}

/// Reads a whole text file, turning an I/O failure into an input error naming the file.
pub fn read_text(path: &Path) -> Result<String, Error> {
    millpath::io::read_text(path)
}

/// Files a G-code program may need (RS274/NGC subroutines, Fanuc subprograms, a tool table).
#[derive(Debug, Clone, clap::Args)]
pub struct ProgramFiles {
    /// Folders searched for subroutine files `NAME.ngc` (after the program's folder),
    /// separated by ':' (LinuxCNC's SUBROUTINE_PATH); Fanuc programs look there for
    /// subprogram files `O1000.nc` or `1000.nc`.
    #[arg(long, value_delimiter = ':')]
    pub subroutine_path: Vec<PathBuf>,
    /// A LinuxCNC tool table (tool.tbl, mm): G43 takes its length offsets, T words must name
    /// its tools.
    #[arg(long)]
    pub tool_table: Option<PathBuf>,
    /// Lines the program may run again (in loops, subroutines and after backward jumps)
    /// before it is refused as endless (exit 2, naming the loop): a program that never ends
    /// stops within seconds.
    #[arg(long, default_value_t = millpath::gcode::DEFAULT_STEP_BUDGET)]
    pub step_budget: u64,
}

/// The machine named by `--machine` ([`millpath::job::load_machine`]): a preset name (see
/// `millpath machines`) or the path of a TOML machine profile.
pub fn load_machine(spec: &str) -> Result<Machine, Error> {
    millpath::job::load_machine(spec)
}

/// Prints `value` as one line of JSON on stdout (the `--json` output of every command).
pub fn print_json(value: &impl serde::Serialize) -> Result<(), Error> {
    let text = serde_json::to_string(value).map_err(|e| Error::internal(format!("JSON: {e}")))?;
    print(&text);
    Ok(())
}

/// `OUT.svg` → `OUT.levelK.svg` (the per-level picture K, counted from 1).
pub fn level_path(path: &Path, level: usize) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(|| "preview".into(), |s| s.to_string_lossy().into_owned());
    let ext = path
        .extension()
        .map_or_else(|| "svg".into(), |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}.level{}.{ext}", level + 1))
}

/// Writes the SVG preview of `tp` (all levels, with the side view) to `path` and, when
/// `per_level`, one picture per level beside it (`NAME.level1.svg`, ...). Returns the paths
/// written.
pub fn write_previews(
    path: &Path,
    tp: &millpath::Toolpath,
    outlines: &[millpath::geom::Outline],
    opts: &millpath::report::PreviewOptions,
    per_level: bool,
) -> Result<Vec<PathBuf>, Error> {
    let opts = opts.clone().with_side_view(true);
    let mut written = vec![path.to_path_buf()];
    millpath::io::write_atomic(
        path,
        millpath::report::toolpath_svg(tp, outlines, &opts).as_bytes(),
    )?;
    if per_level && tp.levels.len() > 1 {
        for (i, svg) in millpath::report::level_previews(tp, outlines, &opts)
            .iter()
            .enumerate()
        {
            let p = level_path(path, i);
            millpath::io::write_atomic(&p, svg.as_bytes())?;
            written.push(p);
        }
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn level_paths_and_machines() {
        assert_eq!(
            level_path(Path::new("out/part.svg"), 0),
            PathBuf::from("out/part.level1.svg")
        );
        assert!(load_machine("hsm").is_ok());
        let e = load_machine("no-such-machine").unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("--machine"), "{e}");
        let e = load_machine("/nonexistent/mill.toml").unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let dir = tempfile::tempdir().unwrap();
        let bad = dir.path().join("m.toml");
        std::fs::write(&bad, "name = 3").unwrap();
        assert_eq!(
            load_machine(bad.to_str().unwrap()).unwrap_err().exit_code(),
            2
        );
    }
}
