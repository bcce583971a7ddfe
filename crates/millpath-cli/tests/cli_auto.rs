//! `millpath pocket --strategy auto` writes the program of the fastest verified strategy:
//! checked by running the three strategies one by one and timing each program with
//! `millpath estimate`, independently of `auto`'s own timing. The report lists all three.

use std::process::Output;

mod common;
use common::millpath;

fn ok(o: &Output) -> String {
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn auto_writes_the_fastest_verified_program_and_reports_all_three() {
    let dir = tempfile::tempdir().unwrap();
    // With a finishing pass (2026-11-25: the spiral is then the fastest and unverified).
    let common = [
        "sample:aerospace",
        "--depth",
        "5",
        "--step-down",
        "5",
        "--finish",
        "--cell",
        "0.1",
        "--machine",
        "hsm",
    ];
    let run = |strategy: &str, out: &str, report: &str| {
        let mut a = vec!["pocket"];
        a.extend(common);
        a.extend(["--strategy", strategy, "-o", out, "--report", report]);
        ok(&millpath(&a, dir.path()))
    };
    let stdout = run("auto", "auto.ngc", "auto.json");
    let rep: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("auto.json")).unwrap())
            .unwrap();
    let entries = rep["auto"].as_array().expect("auto entries");
    let names: Vec<&str> = entries
        .iter()
        .map(|e| e["strategy"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["spiral", "offset", "zigzag"]);
    for n in &names {
        assert!(
            stdout
                .lines()
                .any(|l| l.starts_with(&format!("auto: {n}:"))),
            "{stdout}"
        );
    }
    // Each strategy on its own, its program timed by `estimate`.
    let mut best: Option<(String, f64)> = None;
    for (e, n) in entries.iter().zip(&names) {
        run(n, &format!("{n}.ngc"), &format!("{n}.json"));
        let own: serde_json::Value = serde_json::from_str(
            &std::fs::read_to_string(dir.path().join(format!("{n}.json"))).unwrap(),
        )
        .unwrap();
        let verified = own["problems"].as_array().unwrap().is_empty();
        assert_eq!(e["verified"].as_bool(), Some(verified), "{n}");
        assert_eq!(e["why_not"].is_null(), verified, "{n}");
        let est: serde_json::Value = serde_json::from_str(&ok(&millpath(
            &[
                "estimate",
                &format!("{n}.ngc"),
                "--machine",
                "hsm",
                "--json",
            ],
            dir.path(),
        )))
        .unwrap();
        let t = est["cycle_time_s"].as_f64().unwrap();
        let planned = e["cycle_time_s"].as_f64().unwrap();
        assert!(
            (t - planned).abs() < 0.01 * t,
            "{n}: {t} s read back, {planned} s"
        );
        if verified && best.as_ref().is_none_or(|b| t < b.1) {
            best = Some(((*n).to_owned(), t));
        }
    }
    let (fastest, _) = best.expect("a verified strategy");
    assert_eq!(rep["strategy"].as_str(), Some(fastest.as_str()));
    for (e, n) in entries.iter().zip(&names) {
        assert_eq!(e["chosen"].as_bool(), Some(*n == fastest), "{n}");
    }
    let written = std::fs::read(dir.path().join("auto.ngc")).unwrap();
    let own = std::fs::read(dir.path().join(format!("{fastest}.ngc"))).unwrap();
    assert!(
        written == own,
        "auto wrote {fastest}'s program, byte for byte"
    );
}

/// Given the flute length, `auto` tries the adaptive too, at its own defaults (10 %, one level
/// per flute length): the entry's time is that of `--strategy adaptive` run alone with the
/// same flags, its program timed by `estimate`, and its verification the same.
#[test]
fn auto_tries_the_adaptive_where_the_flute_length_is_given() {
    let dir = tempfile::tempdir().unwrap();
    let common = [
        "pocket",
        "sample:aerospace",
        "--depth",
        "5",
        "--flute-length",
        "12",
        "--machine",
        "hsm",
    ];
    let run = |strategy: &str, out: &str, report: &str| {
        let mut a = common.to_vec();
        a.extend(["--strategy", strategy, "-o", out, "--report", report]);
        ok(&millpath(&a, dir.path()));
        let text = std::fs::read_to_string(dir.path().join(report)).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    let rep = run("auto", "auto.ngc", "auto.json");
    let entries = rep["auto"].as_array().expect("auto entries");
    let names: Vec<&str> = entries
        .iter()
        .map(|e| e["strategy"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["spiral", "offset", "zigzag", "adaptive"]);
    let own = run("adaptive", "a.ngc", "a.json");
    assert!((own["stepover_mm"].as_f64().unwrap() - 1.27).abs() < 1e-9);
    let verified = own["problems"].as_array().unwrap().is_empty();
    assert_eq!(entries[3]["verified"].as_bool(), Some(verified));
    let est: serde_json::Value = serde_json::from_str(&ok(&millpath(
        &["estimate", "a.ngc", "--machine", "hsm", "--json"],
        dir.path(),
    )))
    .unwrap();
    let t = est["cycle_time_s"].as_f64().unwrap();
    let planned = entries[3]["cycle_time_s"].as_f64().unwrap();
    assert!(
        (t - planned).abs() < 0.01 * t,
        "{t} s read back, {planned} s"
    );
}
