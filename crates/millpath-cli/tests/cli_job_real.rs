//! Every real drawing in `../shared/real-inputs/files/` made into a whole job from the drawing
//! alone (`millpath job --init`, then `millpath job` in each dialect; the checks are
//! `job_real`'s): a drawing that holds closed outlines gives a program in every dialect that
//! `estimate` times as the report does, `rs274` reads (LinuxCNC) and the whole-job stock check
//! finds holding the drawn part by its tabs; one without is refused by `--init` (exit 2);
//! those in [`KNOWN`] still fail as listed.
//! Minutes in release (the stock simulations of the largest drawings), so ignored:
//! `cargo test --release -p millpath-cli --test cli_job_real -- --ignored --nocapture`
//! prints the table (`MILLPATH_SWEEP_FILES=a.dxf,b.svg` runs only those drawings, without
//! the counts over all of them). A bounded set runs in `./scripts/test` (`cli_real_files.rs`).

#![allow(clippy::print_stderr)] // the per-drawing table

mod job_real;

/// Drawings whose starting job is not made yet: words their failure holds (`job exit` and
/// its code, or the check that refuses the program) and why. Each must still fail so (a fix
/// must take it off the list); none may hang.
const KNOWN: &[(&str, &str, &str)] = &[];

#[test]
#[ignore = "minutes in release: cargo test --release -p millpath-cli --test cli_job_real -- --ignored"]
fn every_real_drawing_is_made_into_a_job_or_refused_clearly() {
    let mut files: Vec<String> = std::fs::read_dir(job_real::dir())
        .expect("folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .filter(|n| !n.ends_with(".md"))
        .collect();
    files.sort();
    assert!(files.len() >= 41, "{files:?}");
    let only: Option<Vec<String>> = std::env::var("MILLPATH_SWEEP_FILES")
        .ok()
        .map(|v| v.split(',').map(str::to_owned).collect());
    if let Some(only) = &only {
        files.retain(|f| only.contains(f));
        assert_eq!(
            files.len(),
            only.len(),
            "MILLPATH_SWEEP_FILES names {only:?}; found {files:?}"
        );
    }
    let work = tempfile::tempdir().expect("work dir");
    // Over two threads, the slowest drawings first (largest files first).
    let mut queue = files.clone();
    queue.sort_by_key(|f| std::fs::metadata(job_real::dir().join(f)).map_or(0, |m| m.len()));
    let results = job_real::on_two_threads(queue, |f| job_real::job_real(f, work.path()));
    let mut failures = Vec::new();
    let mut made = 0;
    for (f, r) in &results {
        let known = KNOWN.iter().find(|k| k.0 == f);
        match (r, known) {
            (Ok(row), None) => {
                made += usize::from(row.refused.is_none());
                eprintln!("{row}");
            }
            (Ok(_), Some(_)) => failures.push(format!("{f}: made now; take it off KNOWN")),
            (Err(e), Some((_, words, why))) => {
                eprintln!("{f:<36} known ({words}): {why}");
                if !e.contains(words) {
                    failures.push(format!("{f}: not the known failure ({words}): {e}"));
                }
            }
            (Err(e), None) => {
                eprintln!("{f:<36} FAILED: {}", e.lines().next().unwrap_or(""));
                failures.push(e.clone());
            }
        }
    }
    assert_eq!(results.len(), files.len());
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    if only.is_some() {
        return;
    }
    // The four drawings without a closed outline are the only ones refused.
    let refused = results
        .iter()
        .filter(|(_, r)| r.as_ref().is_ok_and(|row| row.refused.is_some()))
        .count();
    assert_eq!(refused, 4, "{refused} refused");
    assert_eq!(made + refused + KNOWN.len(), files.len());
}
