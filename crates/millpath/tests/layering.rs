//! The engine's layering, checked on its source: every file's `crate::`, `super::` and `self::`
//! paths (outside `#[cfg(test)]` code, comments and strings) are resolved to the file that
//! defines them, then
//! - no file imports a top-level module of a higher layer than its own (`LAYERS`, lowest
//!   first: the order of ARCHITECTURE.md's table), and
//! - no two files reach each other through imports (no cycle in the file graph).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The engine's top-level modules, lowest layer first. A module may import its own layer and
/// the ones before it.
const LAYERS: &[&str] = &[
    "error",
    "geom",
    "curve",
    "io",
    "toolpath",
    "stock",
    "strategy",
    "machine",
    "motion",
    "gcode",
    "calibrate",
    "report",
    "job",
];

fn source_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
        let path = entry.unwrap().path();
        if path.is_dir() {
            source_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The module path of a source file relative to `src/`: `strategy/pocket/mod.rs` →
/// `["strategy", "pocket"]`, `lib.rs` → `[]`.
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().unwrap();
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_owned());
    }
    parts
}

/// The code of a file without its test module, comments, strings and character literals.
fn code_only(src: &str) -> String {
    let src = src.split("#[cfg(test)]").next().unwrap_or("");
    let b = src.as_bytes();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                i += 2;
                while i + 1 < b.len() && !(b[i] == b'*' && b[i + 1] == b'/') {
                    i += 1;
                }
                i += 2;
            }
            b'r' if matches!(b.get(i + 1), Some(b'#' | b'"'))
                && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_')) =>
            {
                let mut j = i + 1;
                let mut hashes = 0;
                while b.get(j) == Some(&b'#') {
                    hashes += 1;
                    j += 1;
                }
                if b.get(j) != Some(&b'"') {
                    out.push('r');
                    i += 1;
                    continue;
                }
                let close: Vec<u8> = std::iter::once(b'"')
                    .chain((0..hashes).map(|_| b'#'))
                    .collect();
                j += 1;
                while j < b.len() && !b[j..].starts_with(&close) {
                    j += 1;
                }
                i = j + close.len();
                out.push_str("\"\"");
            }
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
                out.push_str("\"\"");
            }
            b'\'' if b.get(i + 2) == Some(&b'\'') || b.get(i + 1) == Some(&b'\\') => {
                // A character literal ('x' or '\n'); a lifetime has no closing quote.
                i += 1;
                while i < b.len() && b[i] != b'\'' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
            }
            c => {
                out.push(c as char);
                i += 1;
            }
        }
    }
    out
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

/// Every path a `use` tree or an inline path starting at `b[i..]` names, each as its segments
/// after the root keyword (`crate::a::{b, c::d}` → `[a, b]`, `[a, c, d]`).
fn paths_at(b: &[u8], mut i: usize, prefix: Vec<String>, out: &mut Vec<Vec<String>>) -> usize {
    let mut segs = prefix;
    loop {
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        if b.get(i) == Some(&b'{') {
            i += 1;
            loop {
                i = paths_at(b, i, segs.clone(), out);
                while i < b.len() && b[i].is_ascii_whitespace() {
                    i += 1;
                }
                match b.get(i) {
                    Some(b',') => i += 1,
                    Some(b'}') => return i + 1,
                    _ => return i,
                }
                while i < b.len() && b[i].is_ascii_whitespace() {
                    i += 1;
                }
                if b.get(i) == Some(&b'}') {
                    return i + 1;
                }
            }
        }
        let start = i;
        while i < b.len() && is_ident(b[i]) {
            i += 1;
        }
        if i > start {
            segs.push(String::from_utf8_lossy(&b[start..i]).into_owned());
        }
        if b[i..].starts_with(b"::") {
            i += 2;
        } else {
            out.push(segs);
            return i;
        }
    }
}

/// The absolute module paths `code` (a file of module `me`) names through `crate::`, `super::`
/// and `self::`.
fn imported_paths(code: &str, me: &[String]) -> Vec<Vec<String>> {
    let b = code.as_bytes();
    let mut out = Vec::new();
    for root in ["crate::", "super::", "self::"] {
        let mut from = 0;
        while let Some(k) = code[from..].find(root) {
            let at = from + k;
            from = at + root.len();
            if at > 0 && (is_ident(b[at - 1]) || b[at - 1] == b':') {
                continue; // part of a longer path (`super::super::x`, `a::self::`)
            }
            let base: Vec<String> = match root {
                "crate::" => Vec::new(),
                "super::" => me[..me.len().saturating_sub(1)].to_vec(),
                _ => me.to_vec(),
            };
            let mut found = Vec::new();
            paths_at(b, from, Vec::new(), &mut found);
            for rel in found {
                let mut abs = base.clone();
                for seg in rel {
                    if seg == "super" {
                        abs.pop();
                    } else if seg != "self" {
                        abs.push(seg);
                    }
                }
                out.push(abs);
            }
        }
    }
    out
}

struct Engine {
    /// Source file (relative to `src/`) → the files its imports resolve to.
    edges: BTreeMap<String, BTreeSet<String>>,
    /// Source file → the absolute paths it imports.
    imports: BTreeMap<String, Vec<Vec<String>>>,
}

fn engine() -> Engine {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&src, &mut files);
    let modules: BTreeMap<Vec<String>, String> = files
        .iter()
        .map(|f| {
            let rel = f.strip_prefix(&src).unwrap();
            (module_path(rel), rel.to_string_lossy().into_owned())
        })
        .collect();
    let code: BTreeMap<&Vec<String>, String> = modules
        .iter()
        .map(|(me, file)| {
            (
                me,
                code_only(&std::fs::read_to_string(src.join(file)).unwrap()),
            )
        })
        .collect();
    // What each module re-exports from its children (`pub use child::{A, b::C}`): the name
    // → the absolute path it stands for, so an import of `geom::Point` reaches `geom/point.rs`.
    let mut reexports: BTreeMap<Vec<String>, BTreeMap<String, Vec<String>>> = BTreeMap::new();
    for (me, text) in &code {
        let b = text.as_bytes();
        let mut from = 0;
        while let Some(k) = text[from..].find("pub use ") {
            let at = from + k + "pub use ".len();
            from = at;
            if ["crate::", "super::", "self::"]
                .iter()
                .any(|r| text[at..].starts_with(r))
            {
                continue;
            }
            let mut found = Vec::new();
            paths_at(b, at, Vec::new(), &mut found);
            for rel in found {
                if let Some(name) = rel.last() {
                    let mut abs = (*me).clone();
                    abs.extend(rel.iter().cloned());
                    reexports
                        .entry((*me).clone())
                        .or_default()
                        .insert(name.clone(), abs);
                }
            }
        }
    }
    let resolve = |p: &[String]| -> Option<&String> {
        let mut p = p.to_vec();
        for _ in 0..8 {
            // The longest prefix that is a module with a file of its own, followed through
            // that module's re-exports.
            let n = (1..=p.len())
                .rev()
                .find(|n| modules.contains_key(&p[..*n]))?;
            match p.get(n).and_then(|name| reexports.get(&p[..n])?.get(name)) {
                Some(target) if target.len() > n + 1 => {
                    let mut next = target.clone();
                    next.extend(p[n + 1..].iter().cloned());
                    p = next;
                }
                _ => return modules.get(&p[..n]),
            }
        }
        None
    };
    let mut edges = BTreeMap::new();
    let mut imports = BTreeMap::new();
    for (me, file) in &modules {
        let paths = imported_paths(&code[me], me);
        let mut to = BTreeSet::new();
        for p in &paths {
            if let Some(t) = resolve(p).filter(|t| *t != file) {
                to.insert(t.clone());
            }
        }
        edges.insert(file.clone(), to);
        imports.insert(file.clone(), paths);
    }
    Engine { edges, imports }
}

#[test]
fn the_parser_finds_grouped_and_relative_paths() {
    let me = [
        "strategy".to_owned(),
        "pocket".to_owned(),
        "spiral".to_owned(),
    ];
    let code = code_only(
        "use crate::geom::{Point, curve::{a, b}};\n// crate::report::x\n\
         let s = \"crate::motion\"; use super::super::stock::X; let t = self::lanes::f();",
    );
    let got = imported_paths(&code, &me);
    let want: Vec<Vec<&str>> = vec![
        vec!["geom", "Point"],
        vec!["geom", "curve", "a"],
        vec!["geom", "curve", "b"],
        vec!["strategy", "stock", "X"],
        vec!["strategy", "pocket", "spiral", "lanes", "f"],
    ];
    assert_eq!(got, want, "parsed {code:?}");
}

#[test]
fn no_module_imports_a_layer_above_its_own() {
    let engine = engine();
    let rank = |top: &str| LAYERS.iter().position(|l| *l == top);
    let mut violations = Vec::new();
    let mut checked = 0;
    for (file, paths) in &engine.imports {
        if file == "lib.rs" {
            continue;
        }
        let top = file.split(['/', '.']).next().unwrap();
        let Some(mine) = rank(top) else {
            violations.push(format!("{file}: module `{top}` is not in LAYERS"));
            continue;
        };
        for p in paths {
            let Some(theirs) = p.first().and_then(|t| rank(t)) else {
                continue;
            };
            checked += 1;
            if theirs > mine {
                violations.push(format!("{file} ({top}) imports crate::{}", p.join("::")));
            }
        }
    }
    assert!(
        checked > 500,
        "only {checked} imports found: the parser is broken"
    );
    assert!(
        violations.is_empty(),
        "imports against the layering:\n{}",
        violations.join("\n")
    );
}

#[test]
fn no_two_files_import_each_other() {
    let engine = engine();
    let edges = &engine.edges;
    assert!(edges.len() > 100, "only {} files found", edges.len());
    // Tarjan's strongly connected components, iteratively.
    let names: Vec<&String> = edges.keys().collect();
    let id: BTreeMap<&String, usize> = names.iter().enumerate().map(|(i, n)| (*n, i)).collect();
    let adj: Vec<Vec<usize>> = names
        .iter()
        .map(|n| {
            edges[*n]
                .iter()
                .filter_map(|t| id.get(t).copied())
                .collect()
        })
        .collect();
    let n = names.len();
    let (mut index, mut low, mut on) = (vec![usize::MAX; n], vec![0; n], vec![false; n]);
    let (mut stack, mut next, mut cycles) = (Vec::new(), 0, Vec::new());
    for root in 0..n {
        if index[root] != usize::MAX {
            continue;
        }
        let mut work = vec![(root, 0)];
        while let Some(&mut (v, ref mut k)) = work.last_mut() {
            if *k == 0 {
                index[v] = next;
                low[v] = next;
                next += 1;
                stack.push(v);
                on[v] = true;
            }
            if let Some(&w) = adj[v].get(*k) {
                *k += 1;
                if index[w] == usize::MAX {
                    work.push((w, 0));
                } else if on[w] {
                    low[v] = low[v].min(index[w]);
                }
                continue;
            }
            work.pop();
            if let Some(&(u, _)) = work.last() {
                low[u] = low[u].min(low[v]);
            }
            if low[v] == index[v] {
                let mut comp = Vec::new();
                while let Some(w) = stack.pop() {
                    on[w] = false;
                    comp.push(names[w].as_str());
                    if w == v {
                        break;
                    }
                }
                if comp.len() > 1 {
                    comp.sort_unstable();
                    cycles.push(comp.join(" <-> "));
                }
            }
        }
    }
    assert!(
        cycles.is_empty(),
        "files importing each other:\n{}",
        cycles.join("\n")
    );
}

/// The modules a library user can name (ARCHITECTURE.md's "Public API"): every other module
/// is `pub(crate)` or private, and its items reach users only through a `pub use` list.
const PUBLIC_MODULES: &[&str] = &[
    "calibrate",
    "curve",
    "error",
    "gcode",
    "gcode::five_axis",
    "geom",
    "io",
    "io::dxf",
    "io::outline_json",
    "io::points",
    "io::svg",
    "job",
    "job::contour",
    "job::drill",
    "job::estimate",
    "job::five_axis",
    "job::optimize",
    "job::part",
    "job::pocket",
    "job::profile",
    "job::rest",
    "job::sweep",
    "job::verify",
    "machine",
    "machine::kinematics",
    "motion",
    "motion::five_axis",
    "motion::table2",
    "report",
    "report::html",
    "report::plots",
    "stock",
    "strategy",
    "strategy::contour",
    "strategy::face",
    "strategy::drill",
    "strategy::pocket",
    "strategy::pocket::builtin",
    "strategy::profile",
    "strategy::rest",
    "toolpath",
];

/// Every `pub mod` of the engine, as a module path, outside test code.
fn public_modules() -> BTreeSet<String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    source_files(&src, &mut files);
    let mut out = BTreeSet::new();
    for f in files {
        let rel = f.strip_prefix(&src).unwrap();
        let me = module_path(rel);
        let code = code_only(&std::fs::read_to_string(&f).unwrap());
        for line in code.lines() {
            let Some(name) = line
                .trim()
                .strip_prefix("pub mod ")
                .and_then(|r| r.strip_suffix(';'))
            else {
                continue;
            };
            let mut path = me.clone();
            path.push(name.trim().to_owned());
            out.insert(path.join("::"));
        }
    }
    out
}

#[test]
fn only_the_curated_modules_are_public() {
    let found = public_modules();
    let want: BTreeSet<String> = PUBLIC_MODULES.iter().map(|s| (*s).to_owned()).collect();
    let extra: Vec<_> = found.difference(&want).collect();
    let missing: Vec<_> = want.difference(&found).collect();
    assert!(
        extra.is_empty() && missing.is_empty(),
        "public modules not in the curated list (make them pub(crate) and re-export what users \
         need, or add them here and to ARCHITECTURE.md): {extra:?}; listed but not public: \
         {missing:?}"
    );
}
