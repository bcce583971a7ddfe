//! A checker of the words and modes each controller accepts, written from the controllers'
//! documented G-code sets and sharing no code with millpath's writer or reader (its own
//! tokenizer, modal state and arc geometry). LinuxCNC programs are checked by LinuxCNC's own
//! `rs274` instead (`rs274_common`).
//!
//! Sources:
//! * **Grbl 1.1** (`gnea/grbl` wiki "Grbl v1.1 Commands" and `grbl/gcode.c`): G0–G3, G4, G10
//!   L2/L20, G17–G19, G20/G21, G28/G30 (.1), G38.2–G38.5, G40, G43.1, G49, G53, G54–G59, G61,
//!   G80, G90/G91, G91.1, G92 (.1), G93/G94; M0 M1 M2 M30 M3 M4 M5 M7 M8 M9 M56; words F I J K
//!   L N P R S T X Y Z. No `P` on G2/G3 (helical turn counts do not exist). Arc radius check
//!   in `gcode.c` (centre format, in mm): refused when `Δr > 0.005` and (`Δr > 0.5` or
//!   `Δr > 0.001·r`). `read_float` keeps 8 significant digits (`MAX_INT_DIGITS`): more are
//!   silently dropped, so a program must not need them. A line holds fewer than 80
//!   characters once spaces and comments are removed (`LINE_BUFFER_SIZE`).
//! * **Fanuc** 0i-MF / 30i (ISO, Series 0i-MODEL F operator's manual, "Preparatory function
//!   list"): `%` framing and an `O` number of four digits; comments in parentheses, upper
//!   case; G2/G3 in the selected plane with its two offsets (I J in G17, I K in G18, J K in
//!   G19) or R, the third axis moving helically; `G04 X` with a decimal point (seconds) or
//!   `P` (ms, integer); `G05.1 Q1`/`Q0` AI contour control; `G43 H`; `G93` inverse time (F on
//!   every feed block); axis and offset words with a decimal point (without "decimal point
//!   programming" `X10` is 10 increments); the end `M30` then `%`. Arc radii: start and end
//!   radius within parameter 3410 (0.01 mm assumed here, a usual setting).
//! * **Sinumerik 840D sl** (Siemens mode, Programming Manual Fundamentals and Job Planning):
//!   `;` comments (no parentheses outside a call); G0–G3, G4 (`F` s or `S` revolutions, in a
//!   block of its own), G17–G19, G40, G53, G54–G57, G500, G60, G64, G641/G642, G70/G71,
//!   G700/G710, G90/G91, G93/G94/G95; `TURN=n` on G2/G3; `CYCLE832(tol, _FINISH, 1)` in a
//!   block of its own; the drilling cycles `CYCLE81(RTP, RFP, SDIS, DP, DPR)`, `CYCLE82(…,
//!   DTB)` and `CYCLE83(…)` (Cycles programming manual: at most 5, 6 and 17 parameters,
//!   numbers or empty, RTP at or above RFP + SDIS above DP) in a block of their own; `T n M6` (D1 default); arc radii within `MD21000
//!   CIRCLE_ERROR_CONST` (0.01 mm) or `MD21010 CIRCLE_ERROR_FACTOR` (0.1 %) of the radius.
#![allow(dead_code)]

use millpath::gcode::Dialect;

const MM_PER_IN: f64 = 25.4;

/// One word of a block.
#[derive(Debug, Clone)]
struct W {
    letter: char,
    text: String,
    value: f64,
}

fn g_allowed(d: Dialect, g: &str) -> bool {
    let list: &[&str] = match d {
        Dialect::Grbl => &[
            "0", "1", "2", "3", "4", "10", "17", "18", "19", "20", "21", "28", "28.1", "30",
            "30.1", "38.2", "38.3", "38.4", "38.5", "40", "43.1", "49", "53", "54", "55", "56",
            "57", "58", "59", "61", "80", "90", "91", "91.1", "92", "92.1", "93", "94",
        ],
        Dialect::Fanuc => &[
            "0", "1", "2", "3", "4", "5.1", "9", "10", "15", "16", "17", "18", "19", "20", "21",
            "28", "40", "41", "42", "43", "43.4", "44", "49", "52", "53", "54", "55", "56", "57",
            "58", "59", "61", "62", "63", "64", "68", "69", "73", "80", "81", "82", "83", "84",
            "85", "86", "87", "88", "89", "90", "91", "92", "93", "94", "95", "98", "99",
        ],
        Dialect::Sinumerik => &[
            "0", "1", "2", "3", "4", "9", "17", "18", "19", "40", "41", "42", "53", "54", "55",
            "56", "57", "500", "60", "64", "641", "642", "70", "71", "700", "710", "90", "91",
            "93", "94", "95",
        ],
        Dialect::LinuxCnc => return true,
    };
    list.contains(&g)
}

fn m_allowed(d: Dialect, m: i64) -> bool {
    match d {
        Dialect::Grbl => [0, 1, 2, 30, 3, 4, 5, 7, 8, 9, 56].contains(&m),
        Dialect::Fanuc => [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 30, 98, 99].contains(&m),
        Dialect::Sinumerik => [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 17, 30].contains(&m),
        Dialect::LinuxCnc => true,
    }
}

fn letters(d: Dialect) -> &'static str {
    match d {
        Dialect::Grbl => "FGIJKLMNPRSTXYZ",
        Dialect::Fanuc => "ABCDFGHIJKMNOPQRSTXYZ",
        Dialect::Sinumerik => "ABCDFGIJKMNSTXYZ",
        Dialect::LinuxCnc => "ABCDFGHIJKLMNPQRSTUVWXYZ",
    }
}

/// `G02` → "2", `G5.1` → "5.1", `G04` → "4".
fn g_name(text: &str) -> String {
    let t = text.trim_start_matches('0');
    let t = if t.starts_with('.') || t.is_empty() {
        format!("0{t}")
    } else {
        t.to_string()
    };
    t.trim_end_matches(".0").to_string()
}

fn significant_digits(text: &str) -> usize {
    let digits: String = text.chars().filter(char::is_ascii_digit).collect();
    digits.trim_start_matches('0').len().max(1)
}

/// Splits a code (comments removed) into words; `Err` names what is not a word.
fn words(code: &str) -> Result<Vec<W>, String> {
    let b: Vec<char> = code.chars().filter(|c| !c.is_whitespace()).collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let letter = b[i];
        if !letter.is_ascii_uppercase() {
            return Err(format!(
                "not a word at {:?}",
                b[i..].iter().collect::<String>()
            ));
        }
        let mut j = i + 1;
        while j < b.len() && (b[j].is_ascii_digit() || b[j] == '.' || b[j] == '-' || b[j] == '+') {
            j += 1;
        }
        let text: String = b[i + 1..j].iter().collect();
        let value: f64 = text
            .parse()
            .map_err(|_| format!("word {letter}{text}: not a number"))?;
        out.push(W {
            letter,
            text,
            value,
        });
        i = j;
    }
    Ok(out)
}

/// The modal state the checker follows.
struct State {
    units: Option<f64>,
    motion: Option<String>,
    plane: String,
    inverse_time: bool,
    feed: Option<f64>,
    pos: [Option<f64>; 3],
    ended: bool,
}

/// Checks `text` as a program for `d`'s controller; `Err` names the line and the rule.
pub fn check(text: &str, d: Dialect) -> Result<(), String> {
    let lines: Vec<&str> = text.lines().collect();
    if d == Dialect::Fanuc {
        let non_empty: Vec<&str> = lines
            .iter()
            .map(|l| l.trim())
            .filter(|l| !l.is_empty())
            .collect();
        if non_empty.first() != Some(&"%") || non_empty.last() != Some(&"%") {
            return Err("fanuc: a program starts and ends with a % line".into());
        }
        let o = non_empty.get(1).copied().unwrap_or("");
        let num = o.split('(').next().unwrap_or("").trim();
        if !(num.len() == 5 && num.starts_with('O') && num[1..].bytes().all(|c| c.is_ascii_digit()))
        {
            return Err(format!(
                "fanuc: second line {o:?} is not an O number of 4 digits"
            ));
        }
    }
    let mut st = State {
        units: None,
        motion: None,
        plane: "17".into(),
        inverse_time: false,
        feed: None,
        pos: [None; 3],
        ended: false,
    };
    for (k, raw) in lines.iter().enumerate() {
        let n = k + 1;
        line(raw, d, &mut st).map_err(|e| format!("{d} line {n} {raw:?}: {e}"))?;
    }
    if !st.ended {
        return Err(format!("{d}: no program end (M2/M30)"));
    }
    Ok(())
}

/// The code of a line with its comments removed (and checked).
fn strip_comments(raw: &str, d: Dialect) -> Result<String, String> {
    match d {
        Dialect::Sinumerik | Dialect::Grbl => {
            let code = raw.split(';').next().unwrap_or("");
            if d == Dialect::Sinumerik {
                let without_call = ["CYCLE832(", "CYCLE81(", "CYCLE82(", "CYCLE83("]
                    .iter()
                    .fold(code.to_string(), |c, name| c.replace(name, ""));
                if without_call.contains('(') {
                    return Err("parentheses outside a call (sinumerik comments are ;)".into());
                }
            }
            Ok(code.to_string())
        }
        Dialect::Fanuc | Dialect::LinuxCnc => {
            let mut code = String::new();
            let mut comment = String::new();
            let mut depth = 0;
            for c in raw.chars() {
                match (c, depth) {
                    ('(', 0) => depth = 1,
                    ('(', _) => return Err("nested comment".into()),
                    (')', 1) => depth = 0,
                    (c, 0) => code.push(c),
                    (c, _) => comment.push(c),
                }
            }
            if depth != 0 {
                return Err("unclosed comment".into());
            }
            if d == Dialect::Fanuc && comment.chars().any(|c| c.is_ascii_lowercase()) {
                return Err("fanuc comments are upper case".into());
            }
            if code.contains(';') {
                return Err("; is not a comment here".into());
            }
            Ok(code)
        }
    }
}

fn line(raw: &str, d: Dialect, st: &mut State) -> Result<(), String> {
    let t = raw.trim();
    if t.is_empty() || t == "%" {
        return Ok(());
    }
    let mut code = strip_comments(t, d)?;
    if d == Dialect::Fanuc && code.trim_start().starts_with('O') {
        return Ok(());
    }
    if st.ended {
        return Err("a block after the program end".into());
    }
    if d == Dialect::Grbl && code.chars().filter(|c| !c.is_whitespace()).count() >= 80 {
        return Err("longer than grbl's 80-character line buffer".into());
    }
    // Sinumerik's two non-word forms.
    let mut turn = None;
    if d == Dialect::Sinumerik {
        if let Some(at) = code.find("CYCLE832(") {
            let args = &code[at + 9..code.find(')').ok_or("CYCLE832 without )")?];
            let parts: Vec<&str> = args.split(',').collect();
            let tol: f64 = parts
                .first()
                .and_then(|p| p.trim().parse().ok())
                .ok_or("CYCLE832's tolerance is not a number")?;
            if !(tol > 0.0 && parts.len() == 3 && parts[1].trim() == "_FINISH") {
                return Err("CYCLE832(tol,_FINISH,1) expected".into());
            }
            let rest = format!(
                "{}{}",
                &code[..at],
                &code[code.find(')').unwrap_or(0) + 1..]
            );
            if words(&rest)?.iter().any(|w| w.letter != 'N') {
                return Err("CYCLE832 in a block of its own".into());
            }
            return Ok(());
        }
        if let Some(at) = code.find("CYCLE8").filter(|_| !code.contains("CYCLE832(")) {
            return sinumerik_drilling(&code, at);
        }
        if let Some(at) = code.find("TURN=") {
            let tail = &code[at + 5..];
            let end = tail.find(char::is_whitespace).unwrap_or(tail.len());
            turn = Some(
                tail[..end]
                    .parse::<u32>()
                    .map_err(|_| "TURN= takes a whole number")?,
            );
            code = format!("{}{}", &code[..at], &tail[end..]);
        }
    }
    let ws = words(&code)?;
    let allowed = letters(d);
    let mut gs: Vec<String> = Vec::new();
    for w in &ws {
        if !allowed.contains(w.letter) {
            return Err(format!(
                "word {}{} not in the dialect's set",
                w.letter, w.text
            ));
        }
        if d == Dialect::Grbl && significant_digits(&w.text) > 8 {
            return Err(format!(
                "{}{}: more than grbl's 8 significant digits",
                w.letter, w.text
            ));
        }
        if d == Dialect::Fanuc && "XYZABCIJKR".contains(w.letter) && !w.text.contains('.') {
            return Err(format!(
                "{}{}: fanuc axis words need a decimal point",
                w.letter, w.text
            ));
        }
        match w.letter {
            'G' => {
                let g = g_name(&w.text);
                if !g_allowed(d, &g) {
                    return Err(format!("G{} not in the dialect's G codes", w.text));
                }
                gs.push(g);
            }
            'M' => {
                if w.value.fract() != 0.0 || !m_allowed(d, w.value as i64) {
                    return Err(format!("M{} not in the dialect's M codes", w.text));
                }
                if [2, 30, 17].contains(&(w.value as i64)) {
                    st.ended = true;
                }
            }
            _ => {}
        }
    }
    let has = |l: char| ws.iter().any(|w| w.letter == l);
    let get = |l: char| ws.iter().find(|w| w.letter == l).map(|w| w.value);
    for g in &gs {
        match g.as_str() {
            "20" | "700" | "70" => st.units = Some(MM_PER_IN),
            "21" | "710" | "71" => st.units = Some(1.0),
            "17" | "18" | "19" => st.plane = g.clone(),
            "93" => st.inverse_time = true,
            "94" => st.inverse_time = false,
            "0" | "1" | "2" | "3" | "73" | "81" | "82" | "83" => st.motion = Some(g.clone()),
            "80" => st.motion = None,
            "5.1"
                if !(ws.len() == 2 + usize::from(has('N'))
                    && ws
                        .iter()
                        .any(|w| w.letter == 'Q' && (w.text == "0" || w.text == "1"))) =>
            {
                return Err("G05.1 Q1 / Q0 in a block of its own".into());
            }
            "43" if d == Dialect::Fanuc && !has('H') => return Err("G43 without H".into()),
            "91" => return Err("incremental G91: this checker follows absolute programs".into()),
            _ => {}
        }
    }
    if gs.iter().any(|g| g == "4") {
        return dwell(d, &ws);
    }
    if let Some(f) = get('F') {
        if f.is_nan() || f <= 0.0 {
            return Err("F must be > 0".into());
        }
        st.feed = Some(f);
    }
    let axes = ['X', 'Y', 'Z'];
    let moving = ws
        .iter()
        .any(|w| axes.contains(&w.letter) || "ABC".contains(w.letter));
    if !moving {
        if has('I') || has('J') || has('K') || has('R') || turn.is_some() {
            return Err("arc words without an end point".into());
        }
        return Ok(());
    }
    let Some(unit) = st.units else {
        return Err("a move before the units are set".into());
    };
    let motion = st
        .motion
        .clone()
        .ok_or("axis words without a motion mode")?;
    let start = st.pos;
    let mut end = start;
    for (i, a) in axes.iter().enumerate() {
        if let Some(v) = get(*a) {
            end[i] = Some(v * unit);
        }
    }
    if motion != "0" {
        if st.inverse_time && !has('F') {
            return Err("G93: every feed block needs its F".into());
        }
        if st.feed.is_none() {
            return Err("a feed move without a feed".into());
        }
    }
    if ["73", "81", "82", "83"].contains(&motion.as_str()) {
        return drilling(st, &ws, &motion, end);
    }
    if motion == "2" || motion == "3" {
        arc(d, st, &ws, start, end, unit, turn)?;
    } else if has('I') || has('J') || has('K') || has('R') || has('P') || turn.is_some() {
        return Err(format!("arc words on a G{motion} block"));
    }
    st.pos = end;
    Ok(())
}

/// A Fanuc drilling cycle block: X Y the hole, Z the bottom, R at or above it, Q > 0 on
/// G73/G83, P in ms (no point) on G82, nothing else but F, G, N; the tool ends above the hole
/// at a level the block does not say.
fn drilling(st: &mut State, ws: &[W], motion: &str, end: [Option<f64>; 3]) -> Result<(), String> {
    let get = |l: char| ws.iter().find(|w| w.letter == l);
    let (Some(z), Some(r)) = (get('Z'), get('R')) else {
        return Err(format!("G{motion} without Z and R"));
    };
    if r.value < z.value {
        return Err(format!("G{motion}: R below Z"));
    }
    match motion {
        "73" | "83" if !get('Q').is_some_and(|q| q.value > 0.0) => {
            return Err(format!("G{motion} without Q > 0"));
        }
        "82" if !get('P').is_some_and(|p| !p.text.contains('.') && p.value >= 0.0) => {
            return Err("G82 without P milliseconds".into());
        }
        _ => {}
    }
    if let Some(w) = ws.iter().find(|w| !"GNXYZRQPF".contains(w.letter)) {
        return Err(format!("{}{} in a drilling cycle", w.letter, w.text));
    }
    if st.feed.is_none() {
        return Err("a drilling cycle without a feed".into());
    }
    st.pos = [end[0], end[1], None];
    Ok(())
}

/// A Sinumerik `CYCLE81/82/83(…)` block (module docs).
fn sinumerik_drilling(code: &str, at: usize) -> Result<(), String> {
    let open = code.find('(').ok_or("a cycle without (")?;
    let close = code.rfind(')').ok_or("a cycle without )")?;
    let name = &code[at..open];
    let max = match name {
        "CYCLE81" => 5,
        "CYCLE82" => 6,
        "CYCLE83" => 17,
        _ => return Err(format!("{name}: not a drilling cycle of the 840D")),
    };
    let params: Vec<Option<f64>> = code[open + 1..close]
        .split(',')
        .map(|p| {
            let t = p.trim();
            if t.is_empty() {
                Ok(None)
            } else {
                t.parse()
                    .map(Some)
                    .map_err(|_| format!("{name}: {t} is not a number"))
            }
        })
        .collect::<Result<_, _>>()?;
    if params.len() > max {
        return Err(format!("{name}: more than {max} parameters"));
    }
    let p = |k: usize| params.get(k).copied().flatten();
    let (Some(rtp), Some(rfp)) = (p(0), p(1)) else {
        return Err(format!("{name} without RTP and RFP"));
    };
    let r = rfp + p(2).unwrap_or(0.0);
    let dp = p(3)
        .or(p(4).map(|dpr| rfp - dpr))
        .ok_or("a cycle without DP or DPR")?;
    if !(rtp >= r && r > dp) {
        return Err(format!("{name}: RTP at or above RFP + SDIS above DP"));
    }
    let rest = format!("{}{}", &code[..at], &code[close + 1..]);
    if words(&rest)?.iter().any(|w| w.letter != 'N') {
        return Err(format!("{name} in a block of its own"));
    }
    Ok(())
}

fn dwell(d: Dialect, ws: &[W]) -> Result<(), String> {
    let other = |ok: &str| ws.iter().any(|w| !ok.contains(w.letter));
    match d {
        Dialect::Grbl | Dialect::LinuxCnc
            if other("NGP") || !ws.iter().any(|w| w.letter == 'P') =>
        {
            Err("G4 P seconds".into())
        }
        Dialect::Fanuc => {
            let x = ws.iter().find(|w| w.letter == 'X');
            let p = ws.iter().find(|w| w.letter == 'P');
            match (x, p) {
                (Some(x), None) if x.text.contains('.') && !other("NGX") => Ok(()),
                (None, Some(p)) if !p.text.contains('.') && !other("NGP") => Ok(()),
                _ => Err("G04 X seconds (with a point) or P milliseconds".into()),
            }
        }
        Dialect::Sinumerik if other("NGFS") => Err("G4 F/S in a block of its own".into()),
        _ => Ok(()),
    }
}

#[allow(clippy::too_many_arguments)]
fn arc(
    d: Dialect,
    st: &State,
    ws: &[W],
    start: [Option<f64>; 3],
    end: [Option<f64>; 3],
    unit: f64,
    turn: Option<u32>,
) -> Result<(), String> {
    let (u, v, offs, normal_off) = match st.plane.as_str() {
        "17" => (0, 1, ['I', 'J'], 'K'),
        "18" => (2, 0, ['K', 'I'], 'J'),
        _ => (1, 2, ['J', 'K'], 'I'),
    };
    let has = |l: char| ws.iter().any(|w| w.letter == l);
    let get = |l: char| ws.iter().find(|w| w.letter == l).map(|w| w.value * unit);
    if has(normal_off) {
        return Err(format!(
            "{normal_off} is not an offset of plane G{}",
            st.plane
        ));
    }
    if has('P') && matches!(d, Dialect::Grbl | Dialect::Fanuc | Dialect::Sinumerik) {
        return Err("no P word on G2/G3 in this dialect".into());
    }
    if turn.is_some() && d != Dialect::Sinumerik {
        return Err("TURN= is sinumerik's".into());
    }
    let (Some(su), Some(sv)) = (start[u], start[v]) else {
        return Err("an arc from an unknown position".into());
    };
    let eu = end[u].unwrap_or(su);
    let ev = end[v].unwrap_or(sv);
    if has('R') {
        if has(offs[0]) || has(offs[1]) {
            return Err("R with I/J/K".into());
        }
        let r = get('R').unwrap_or(0.0).abs();
        let h = 0.5 * (eu - su).hypot(ev - sv);
        if h > r + 1e-9 || h == 0.0 {
            return Err("R cannot reach the end point".into());
        }
        return Ok(());
    }
    if !(has(offs[0]) || has(offs[1])) {
        return Err("an arc without its centre offsets".into());
    }
    let cu = su + get(offs[0]).unwrap_or(0.0);
    let cv = sv + get(offs[1]).unwrap_or(0.0);
    let r1 = (su - cu).hypot(sv - cv);
    let r2 = (eu - cu).hypot(ev - cv);
    let delta = (r1 - r2).abs();
    let ok = match d {
        Dialect::Grbl => !(delta > 0.005 && (delta > 0.5 || delta > 0.001 * r1)),
        Dialect::Fanuc => delta <= 0.01,
        Dialect::Sinumerik => delta <= 0.01_f64.max(0.001 * r1.max(r2)),
        Dialect::LinuxCnc => true,
    };
    if !ok {
        return Err(format!(
            "start radius {r1} mm and end radius {r2} mm differ too much"
        ));
    }
    if r1 < 1e-6 {
        return Err("a zero-radius arc".into());
    }
    Ok(())
}

/// The self-test: the checker refuses what each controller refuses (so the program tests
/// that use it can fail).
pub fn self_test() {
    let grbl_ok = "; x\nG17 G21 G90 G94\nG0 X0 Y0 Z1\nG1 Z0 F100\nG2 X10 Y0 I5 J0\nM2\n";
    assert_eq!(check(grbl_ok, Dialect::Grbl), Ok(()));
    for bad in [
        "G17 G21 G90\nG0 X0 Y0 Z0\nG2 X10 Y0 I5 J0 P2 F100\nM2\n",
        "G17 G21 G90\nG0 X0 Y0 Z0\nG2 X10 Y0 I5.01 J0 F100\nM2\n",
        "G17 G21 G90\nG64 P0.01\nM2\n",
        "G17 G21 G90\nT1 M6\nM2\n",
        "G17 G21 G90\nG0 X0.123456789\nM2\n",
        "G17 G21 G90\nG0 X0 Y0 Z0\nG1 X1\nM2\n",
    ] {
        assert!(check(bad, Dialect::Grbl).is_err(), "grbl accepted {bad}");
    }
    let fanuc_ok = "%\nO0001 (A)\nG17 G21 G90\nG0 X0. Y0. Z1.\nG1 Z0. F100.\nG3 X10. Y0. I5. J0.\nG04 X0.5\nM30\n%\n";
    assert_eq!(check(fanuc_ok, Dialect::Fanuc), Ok(()));
    for bad in [
        fanuc_ok.replace("X10.", "X10"),
        fanuc_ok.replace("O0001 (A)", "O0001 (a)"),
        fanuc_ok.replace("%\nO0001", "O0001"),
        fanuc_ok.replace("G04 X0.5", "G04 X1"),
        fanuc_ok.replace("G90", "G90 G61.1"),
    ] {
        assert!(check(&bad, Dialect::Fanuc).is_err(), "fanuc accepted {bad}");
    }
    let sin_ok = "; a\nG17 G710 G90\nCYCLE832(0.01,_FINISH,1)\nG0 X0 Y0 Z1\nG1 Z0 F100\nG3 X0 Y0 Z-1 I5 J0 TURN=2\nG4 F0.5\nM30\n";
    assert_eq!(check(sin_ok, Dialect::Sinumerik), Ok(()));
    for bad in [
        sin_ok.replace("; a", "(a)"),
        sin_ok.replace("G4 F0.5", "G4 F0.5 X1"),
        sin_ok.replace("G710", "G21"),
        sin_ok.replace("CYCLE832(0.01,_FINISH,1)", "G64 P0.01"),
    ] {
        assert!(
            check(&bad, Dialect::Sinumerik).is_err(),
            "sinumerik accepted {bad}"
        );
    }
    // Drilling cycles.
    let fanuc_drill = "%\nO0001\nG17 G21 G90\nG0 X0. Y0. Z5.\n\
                       G98 G83 X10. Y5. Z-8. R1. Q2. F200.\nG82 X20. Z-8. R1. P500\nG80\nM30\n%\n";
    assert_eq!(check(fanuc_drill, Dialect::Fanuc), Ok(()));
    for bad in [
        fanuc_drill.replace(" R1. Q2.", " Q2."),
        fanuc_drill.replace("Q2.", "Q0."),
        fanuc_drill.replace("P500", "P0.5"),
        fanuc_drill.replace("R1. Q2.", "R-9. Q2."),
    ] {
        assert!(check(&bad, Dialect::Fanuc).is_err(), "fanuc accepted {bad}");
    }
    let sin_drill = "; a\nG17 G710 G90\nG0 X0 Y0 Z5\nF200\nCYCLE81(5,1,0,-8)\n\
                     CYCLE83(5,1,0,-8,,-1,,2,0,0,1,1,,,,,0.254)\nM30\n";
    assert_eq!(check(sin_drill, Dialect::Sinumerik), Ok(()));
    for bad in [
        sin_drill.replace("CYCLE81(5,1,0,-8)", "CYCLE81(0,1,0,-8)"),
        sin_drill.replace("CYCLE81(5,1,0,-8)", "CYCLE81(5,1,0,-8,,1)"),
        sin_drill.replace("CYCLE81(5,1,0,-8)", "G0 X1 CYCLE81(5,1,0,-8)"),
    ] {
        assert!(
            check(&bad, Dialect::Sinumerik).is_err(),
            "sinumerik accepted {bad}"
        );
    }
    assert!(
        check(
            "G17 G21 G90\nG0 X0 Y0 Z5\nG81 X1 Y1 Z-1 R1 F100\nM2\n",
            Dialect::Grbl
        )
        .is_err()
    );
}
