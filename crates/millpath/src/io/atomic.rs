//! Atomic file output: write to a temporary file beside the target, then rename.
//!
//! An error while producing the content leaves no output file and does not touch an existing
//! file of the same name.

use crate::error::{Error, InputError};
use std::io::Write;
use std::path::Path;

/// Writes `bytes` to `path` atomically.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    write_atomic_with(path, |w| w.write_all(bytes).map_err(|e| io_error(path, &e)))
}

/// Writes to `path` atomically through `fill`, which gets a buffered writer on a temporary
/// file in the same folder. If `fill` fails, the temporary file is removed and `path` is left
/// as it was.
pub fn write_atomic_with<F>(path: &Path, fill: F) -> Result<(), Error>
where
    F: FnOnce(&mut dyn Write) -> Result<(), Error>,
{
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".to_owned());
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let file = std::fs::File::create(&tmp).map_err(|e| io_error(path, &e))?;
        let mut w = std::io::BufWriter::new(file);
        fill(&mut w)?;
        let file = w.into_inner().map_err(|e| io_error(path, e.error()))?;
        file.sync_all().map_err(|e| io_error(path, &e))?;
        std::fs::rename(&tmp, path).map_err(|e| io_error(path, &e))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

fn io_error(path: &Path, e: &std::io::Error) -> Error {
    Error::Input(
        InputError::new("output file", path.display()).expected(format!("a writable path ({e})")),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_existing_file_untouched() {
        let dir = std::env::temp_dir().join(format!("millpath-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let target = dir.join("out.ngc");
        std::fs::write(&target, b"old").unwrap();
        let r = write_atomic_with(&target, |w| {
            w.write_all(b"half").unwrap();
            Err(Error::internal("boom"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "temp file left behind"
        );
        write_atomic(&target, b"new").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
