//! Atomic file output: write to a temporary file beside the target, then rename.
//!
//! An error while producing the content leaves no output file and does not touch an existing
//! file of the same name.
//!
//! A path that names something other than a file (`/dev/null`, `/dev/stdout`, a FIFO) is
//! written in place, once the whole content is produced in memory: renaming a file onto it
//! would replace the device. A symbolic link is followed: the file it points to is replaced,
//! the link stays.

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
    if let Ok(m) = std::fs::metadata(path)
        && !m.is_file()
        && !m.is_dir()
    {
        let mut buf = Vec::new();
        fill(&mut buf)?;
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(|e| io_error(path, &e))?;
        return f
            .write_all(&buf)
            .and_then(|()| f.flush())
            .map_err(|e| io_error(path, &e));
    }
    let resolved;
    let path = if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
        resolved = std::fs::canonicalize(path).map_err(|e| io_error(path, &e))?;
        resolved.as_path()
    } else {
        path
    };
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

    #[cfg(unix)]
    #[test]
    fn devices_are_written_in_place_and_links_followed() {
        use std::os::unix::fs::FileTypeExt;
        let dir = std::env::temp_dir().join(format!("millpath-link-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // A FIFO stands for /dev/null and /dev/stdout: not a file, written in place.
        let fifo = dir.join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let reader = {
                let fifo = fifo.clone();
                std::thread::spawn(move || std::fs::read(fifo).unwrap())
            };
            write_atomic(&fifo, b"through the pipe").unwrap();
            assert_eq!(reader.join().unwrap(), b"through the pipe");
            assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
        }
        let target = dir.join("real.ngc");
        let link = dir.join("link.ngc");
        std::fs::write(&target, b"old").unwrap();
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
