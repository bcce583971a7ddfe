//! LinuxCNC's standalone interpreter `rs274` (Debian package linuxcnc-uspace; `.ci/run`
//! installs it) as a verifier shared by the G-code and contour tests. When `rs274` is missing
//! the tests that call it FAIL, with an install message.

use std::io::Write;
use std::process::Command;

/// Runs rs274 on `text`; Ok(stdout) or Err(stderr).
pub fn rs274(text: &str) -> Result<String, String> {
    // rs274 instances running at the same time crash each other (status None seen when the
    // tests ran in parallel): one at a time.
    static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _guard = ONE_AT_A_TIME
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let mut file = tempfile::Builder::new().suffix(".ngc").tempfile().unwrap();
    file.write_all(text.as_bytes()).unwrap();
    file.flush().unwrap();
    let out = Command::new("rs274")
        .arg("-g")
        .arg(file.path())
        .output()
        .unwrap_or_else(|e| {
            panic!(
                "cannot run `rs274` ({e}): LinuxCNC's standalone interpreter is required for this \
             test; install the Debian package linuxcnc-uspace (CI does)"
            )
        });
    let stderr = String::from_utf8_lossy(&out.stderr).to_string();
    // rs274 prints "executing" on stderr for every run; anything else is a message.
    let messages: Vec<&str> = stderr
        .lines()
        .filter(|l| l.trim() != "executing" && !l.trim().is_empty())
        .collect();
    if out.status.success() && messages.is_empty() {
        Ok(String::from_utf8_lossy(&out.stdout).to_string())
    } else {
        use std::os::unix::process::ExitStatusExt;
        Err(format!(
            "status {:?} (signal {:?}): {}",
            out.status.code(),
            out.status.signal(),
            messages.join("\n")
        ))
    }
}
