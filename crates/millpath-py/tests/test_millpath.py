"""millpath's Python package against the `millpath` CLI (same G-code bytes, same reports)
and against the engine's own verifier.

The CLI is `$MILLPATH_CLI`, else `target/debug/millpath` (built by `cargo test --workspace`,
which `scripts/test` runs first). The real drawings are in ../shared/real-inputs/files beside
the clone; a missing CLI or folder fails the tests, it does not skip them.
"""

import json
import os
import subprocess
import threading
from pathlib import Path

import numpy as np
import pytest

import millpath

ROOT = Path(__file__).resolve().parents[3]
CLI = Path(os.environ.get("MILLPATH_CLI", ROOT / "target" / "debug" / "millpath"))
REAL = ROOT.parent / "shared" / "real-inputs" / "files"
T_PART = REAL / "lc_t-part.dxf"
POCKET_ARGS = dict(depth=5, step_down=5)


def cli(*args, check=True):
    assert CLI.is_file(), f"the millpath CLI is missing at {CLI} (run cargo build first)"
    r = subprocess.run([str(CLI), *map(str, args)], capture_output=True, text=True)
    if check:
        assert r.returncode == 0, r.stderr
    return r


def flags(kwargs):
    out = []
    for k, v in kwargs.items():
        flag = "--" + k.replace("_", "-")
        if v is True:
            out.append(flag)
        elif v is not False and v is not None:
            out += [flag, str(v)]
    return out


def cli_pocket(tmp_path, outline, **kwargs):
    ngc, rep = tmp_path / "cli.ngc", tmp_path / "cli.json"
    cli("pocket", outline, *flags(kwargs), "-o", ngc, "--report", rep)
    return ngc.read_bytes(), json.loads(rep.read_text())


@pytest.mark.parametrize("strategy", ["spiral", "offset", "zigzag"])
def test_pocket_equals_cli(tmp_path, strategy):
    r = millpath.pocket("sample:aerospace", strategy=strategy, **POCKET_ARGS)
    gcode, report = cli_pocket(tmp_path, "sample:aerospace", strategy=strategy, **POCKET_ARGS)
    assert r.gcode.encode() == gcode
    assert r.report == report
    assert r.cycle_time_s == report["cycle_time_s"] > 0
    assert r.strategy == strategy


def test_pocket_adaptive_both_ways_equals_cli(tmp_path):
    kw = dict(POCKET_ARGS, strategy="adaptive", stepover="0.4", both_ways=True)
    r = millpath.pocket("sample:aerospace", **kw)
    gcode, report = cli_pocket(tmp_path, "sample:aerospace", **kw)
    assert r.gcode.encode() == gcode
    assert r.report == report
    assert report["verification"]["uncut_area_mm2"] <= report["verification"]["uncut_tolerance_mm2"]
    climb = millpath.pocket("sample:aerospace", **dict(kw, both_ways=False))
    assert r.gcode != climb.gcode


def test_pocket_adaptive_defaults_equal_cli(tmp_path):
    # Neither stepover nor step_down given: the adaptive's own (10 %, the flute length).
    kw = dict(strategy="adaptive", tool_diameter=4, depth=2, flute_length=2)
    r = millpath.pocket(T_PART, **kw)
    gcode, report = cli_pocket(tmp_path, T_PART, **kw)
    assert r.gcode.encode() == gcode
    assert r.report == report
    assert report["stepover_mm"] == pytest.approx(0.4)
    assert report["verification"]["uncut_area_mm2"] <= report["verification"]["uncut_tolerance_mm2"]


def test_pocket_adaptive_lift_equals_cli(tmp_path):
    kw = dict(strategy="adaptive", tool_diameter=4, depth=2, flute_length=2, lift=0.2)
    r = millpath.pocket(T_PART, **kw)
    gcode, report = cli_pocket(tmp_path, T_PART, **kw)
    assert r.gcode.encode() == gcode
    # Some link rises by the whole lift over the level at z = -2.
    assert "Z-1.8\n" in r.gcode
    assert "Z-1.8\n" not in millpath.pocket(T_PART, **dict(kw, lift=0)).gcode


def test_pocket_auto_tries_the_adaptive_given_the_flute_length(tmp_path):
    kw = dict(POCKET_ARGS, strategy="auto", flute_length=12)
    r = millpath.pocket("sample:aerospace", **kw)
    gcode, report = cli_pocket(tmp_path, "sample:aerospace", **kw)
    assert r.gcode.encode() == gcode
    assert [a["strategy"] for a in report["auto"]] == ["spiral", "offset", "zigzag", "adaptive"]


def test_pocket_real_drawing_other_dialect_equals_cli(tmp_path):
    assert REAL.is_dir(), f"real inputs missing: {REAL}"
    kw = dict(strategy="auto", tool_diameter=4, depth=2, step_down=2, dialect="fanuc",
              units="in", tool_number=3)
    r = millpath.pocket(T_PART, **kw)
    gcode, report = cli_pocket(tmp_path, T_PART, **kw)
    assert r.gcode.encode() == gcode
    assert r.report == report
    assert r.note and "lc_t-part.dxf" in r.note
    tried = r.report.get("auto") or r.report["pockets"][0]["auto"]
    assert [e["strategy"] for e in tried] == ["spiral", "offset", "zigzag"]


def test_rest_pass_equals_cli_and_cuts_what_the_large_tool_left(tmp_path):
    big = millpath.pocket("sample:aerospace", tool_diameter=12.7, **POCKET_ARGS)
    prev = tmp_path / "big.ngc"
    prev.write_text(big.gcode)
    kw = dict(tool_diameter=4, rest_from=prev, **POCKET_ARGS)
    r = millpath.pocket("sample:aerospace", **kw)
    ngc = tmp_path / "cli.ngc"
    out = cli("pocket", "sample:aerospace", *flags(kw), "-o", ngc)
    assert r.gcode.encode() == ngc.read_bytes()
    assert r.strategy == "rest"
    assert r.report["previous_tool_diameter_mm"] == 12.7
    # The 12.7 mm tool leaves the four r 6 corners: material within the 4 mm tool's reach,
    # cut by a few short runs, and nothing of it left after both programs.
    assert r.report["left_mm2"] > 1.0
    assert 1 <= r.report["runs"] <= 8
    assert 0 < r.report["cut_length_mm"] < 200
    assert r.note.splitlines()[-1] in out.stdout + out.stderr
    # An unreadable previous program is bad input, named with where it came from.
    with pytest.raises(millpath.InputError, match="rest-from"):
        millpath.pocket("sample:aerospace", tool_diameter=4, rest_from=tmp_path / "none.ngc")


PLATE = REAL / "wro_Plate_3.DXF"


def cli_drill(tmp_path, drawing, **kwargs):
    ngc, rep = tmp_path / "cli.ngc", tmp_path / "cli.json"
    cli("drill", drawing, *flags(kwargs), "-o", ngc, "--report", rep)
    return ngc.read_bytes(), json.loads(rep.read_text())


@pytest.mark.parametrize(
    "kw",
    [
        dict(tool_diameter=3, depth=5, through=True, peck=2),
        dict(tool_diameter=4, depth=4, dialect="sinumerik", stay_at_retract=True),
        dict(tool_diameter=3, depth=3, chip_break=1, dialect="fanuc", units="in", drill_only=True),
        dict(tool_diameter=2, depth=2, dialect="grbl", min_diameter=3.5, feed="8ipm"),
    ],
)
def test_drill_equals_cli(tmp_path, kw):
    assert REAL.is_dir(), f"real inputs missing: {REAL}"
    r = millpath.drill(PLATE, **kw)
    gcode, report = cli_drill(tmp_path, PLATE, **kw)
    assert r.gcode.encode() == gcode
    assert r.report == report
    assert r.cycle_time_s == report["cycle_time_s"] > 0
    assert r.note and "wro_Plate_3.DXF" in r.note
    # The holes cut, in cutting order, as the report lists them.
    cut = [h for h in report["holes"] if h["operation"] != "skipped"]
    assert r.holes.shape == (len(cut), 3)
    np.testing.assert_allclose(r.holes, [[h["x"], h["y"], h["diameter_mm"]] for h in cut])
    assert report["max_center_error_mm"] <= 0.01 and report["max_diameter_error_mm"] <= 0.01
    # `estimate` of the written program (its dialect found from the text) is the report's.
    e = millpath.estimate(r.gcode, machine="hsm")
    assert e.cycle_time_s == pytest.approx(r.cycle_time_s, rel=1e-9)


def test_drill_bad_input_names_the_flag():
    with pytest.raises(millpath.InputError, match="--peck"):
        millpath.drill(PLATE, peck=0)
    with pytest.raises(millpath.InputError, match="--min-diameter"):
        millpath.drill(PLATE, min_diameter=40)
    with pytest.raises(TypeError):
        millpath.drill(PLATE, no_such_flag=1)


def test_toolpath_arrays_and_trajectory():
    r = millpath.pocket("sample:aerospace", **POCKET_ARGS)
    tp = r.toolpath
    pts = tp.points
    assert pts.dtype == np.float64 and pts.shape == (len(tp) + 1, 3)
    assert tp.feeds.shape == tp.rapid.shape == (len(tp),)
    assert np.isnan(tp.feeds[tp.rapid]).all() and (tp.feeds[~tp.rapid] > 0).all()
    # The cutting length from the array's chords can only be <= the arcs' true length.
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1)
    assert seg[~tp.rapid].sum() <= tp.cut_length_mm * (1 + 1e-9)
    assert pts[:, 2].min() == pytest.approx(-5.0, abs=1e-9)
    tr = tp.trajectory(machine="hsm", dt=0.01)
    n = len(tr["t"])
    assert tr["position"].shape == tr["velocity"].shape == (n, 3)
    assert np.all(np.diff(tr["t"]) > 0) and np.all(tr["s"] >= 0)
    # The planner's time and the time the trajectory spans agree (it is sampled to the end).
    assert tr["t"][-1] == pytest.approx(r.cycle_time_s, rel=0.05)
    np.testing.assert_allclose(tr["position"][-1], pts[-1], atol=1e-6)
    # Never faster than the fastest programmed feed on a cut, or a rapid.
    assert tr["feed"].max() > 0


def test_pocket_from_arrays_passes_the_verifier():
    outer = np.array([[0, 0], [60, 0], [60, 40], [0, 40]], float)
    island = np.array([[25, 15], [25, 25], [35, 25], [35, 15]], float)
    r = millpath.pocket([outer, island], tool_diameter=6, depth=3, step_down=3)
    v = millpath.verify(r.gcode, [outer, island], tool_diameter=6)
    assert v.passed, v.problems
    # The tool the program's header names when none is given, as `millpath verify` does
    # (it was 12.7 mm, which gouges these walls).
    own = millpath.verify(r.gcode, [outer, island])
    assert own.passed, own.problems
    assert own.report == v.report
    assert v.report["verification"]["uncut_area_mm2"] < 1.0
    # The same program cut with a bigger tool than planned gouges the walls.
    bad = millpath.verify(r.gcode, [outer, island], tool_diameter=10)
    assert not bad.passed and bad.problems


def test_input_errors_carry_the_cli_message():
    cases = [
        dict(tool_diameter=-1),
        dict(strategy="trochoidal"),
        dict(feed="fast"),
        dict(dialect="heidenhain"),
        dict(select="9"),
    ]
    for kw in cases:
        with pytest.raises(millpath.InputError) as e:
            millpath.pocket("sample:aerospace", **kw)
        assert isinstance(e.value, ValueError)
        r = cli("pocket", "sample:aerospace", *flags(kw), check=False)
        if kw.get("dialect") is None:  # clap words the dialect's refusal itself
            assert r.returncode == 2
            assert r.stderr.strip().splitlines()[-1] == f"error: {e.value}", kw
    with pytest.raises(millpath.InputError, match="outline file"):
        millpath.pocket("part.step")
    with pytest.raises(TypeError, match="tool_diam"):
        millpath.pocket("sample:aerospace", tool_diam=3)
    assert not issubclass(millpath.InternalError, ValueError)
    assert issubclass(millpath.InternalError, RuntimeError)


def test_profile_equals_cli(tmp_path):
    assert REAL.is_dir(), f"real inputs missing: {REAL}"
    kw = dict(tabs="auto", stock_to_leave=0.3, entry="helix", tool_diameter=6, depth=6,
              step_down=2)
    r = millpath.profile(T_PART, **kw)
    ngc, rep = tmp_path / "p.ngc", tmp_path / "p.json"
    cli("profile", T_PART, *flags(kw), "-o", ngc, "--report", rep)
    assert r.gcode.encode() == ngc.read_bytes()
    assert r.report == json.loads(rep.read_text())
    assert r.cycle_time_s == r.report["cycle_time_s"] > 0
    # Each of the three outlines held by its two tabs, as the stock simulation finds.
    assert [o["tabs"]["hold"] for o in r.report["outlines"]] == ["held by 2 bridges"] * 3
    assert len(r.report["tabs"]) == 6
    # The same flags in another dialect and units, and a bad flag named as the CLI names it.
    f = millpath.profile(T_PART, side="on", depth=1, step_down=1, dialect="fanuc", units="in")
    cli("profile", T_PART, "--side", "on", "--depth", "1", "--step-down", "1",
        "--dialect", "fanuc", "--units", "in", "-o", ngc)
    assert f.gcode.encode() == ngc.read_bytes()
    with pytest.raises(millpath.InputError, match="--tabs"):
        millpath.profile(T_PART, tabs="many")
    bad = cli("profile", T_PART, "--tabs", "many", check=False)
    assert bad.returncode == 2 and "--tabs" in bad.stderr


def test_contour_equals_cli(tmp_path):
    r = millpath.contour(sample=True, tolerance=0.01, arcs=True)
    ngc, rep = tmp_path / "c.ngc", tmp_path / "c.json"
    cli("contour", "--sample", "--tolerance", "0.01", "--arcs", "-o", ngc, "--report", rep)
    assert r.gcode.encode() == ngc.read_bytes()
    assert r.report == json.loads(rep.read_text())
    assert r.report["max_deviation_mm"] <= 0.01
    js = json.loads(cli("contour", "--sample", "--tolerance", "0.01", "--arcs", "--json").stdout)
    assert r.cycle_time_s == js["cycle_time_s"]
    # Points as an array read as the same CSV file does.
    pts = np.array([[60, 345, 1], [100, 325, 1], [140, 295, 1], [180, 245, 1],
                    [340, 205, 2], [260, 385, 2], [140, 375, 2], [60, 345, 2]], float)
    csv = tmp_path / "pts.csv"
    csv.write_text("x,y,group\n" + "".join(f"{x:g},{y:g},{g:g}\n" for x, y, g in pts))
    a = millpath.contour(csv, tool_diameter=6, tolerance=0.01)
    cli("contour", csv, "--tool-diameter", "6", "--tolerance", "0.01", "-o", ngc)
    assert a.gcode.encode() == ngc.read_bytes()
    b = millpath.contour(pts, tool_diameter=6, tolerance=0.01)
    # The same program but for its title line, which names the input.
    assert b.gcode.splitlines()[1:] == a.gcode.splitlines()[1:]
    assert "points" in b.gcode.splitlines()[0]
    with pytest.raises(millpath.InputError, match="decimals"):
        millpath.contour(sample=True, tolerance=0.0001, decimals=3)


def test_estimate_equals_cli(tmp_path):
    r = millpath.pocket("sample:aerospace", **POCKET_ARGS)
    f = tmp_path / "p.ngc"
    f.write_text(r.gcode)
    js = json.loads(cli("estimate", f, "--machine", "hsm", "--json").stdout)
    for program in (r.gcode, f, str(f)):
        e = millpath.estimate(program, machine="hsm")
        assert e.cycle_time_s == js["cycle_time_s"]
    # The pocket's own report times the written program the same way.
    assert e.cycle_time_s == r.cycle_time_s
    np.testing.assert_allclose(e.toolpath.points[-1], r.toolpath.points[-1], atol=1e-3)
    with pytest.raises(millpath.InputError, match="machine"):
        millpath.estimate(r.gcode, machine="no-such-mill")


def test_estimate_five_axis_equals_cli(tmp_path):
    """A five-axis program (A and C words, trivkins): the rotary axes are planned as the CLI
    plans them, within 5 % of LinuxCNC's own time (3.699 s, tests/data/five_axis/times.csv),
    and a rotary-only move takes its trapezoid by hand: 90 deg at F3600 deg/min (60 deg/s)
    with 900 deg/s^2, 1.5 s + 60/900 s."""
    text = "; XYZAC\nG21 G90 G94\nG64\nG1 X10 A30 F600\nG1 C90 F3600\nG1 X20 Y10 A0 C180 F1200\nM2\n"
    f = tmp_path / "five.ngc"
    f.write_text(text)
    js = json.loads(cli("estimate", f, "--machine", "linuxcnc-time", "--json").stdout)
    for program in (text, f):
        e = millpath.estimate(program, machine="linuxcnc-time")
        assert e.cycle_time_s == js["cycle_time_s"]
    assert abs(e.cycle_time_s / 3.699 - 1) < 0.05
    one = millpath.estimate("G21 G90 G61.1\nG1 C90 F3600\nM2\n", machine="linuxcnc-time")
    assert abs(one.cycle_time_s - (1.5 + 60 / 900)) < 2e-3


def test_optimize_five_axis_equals_cli(tmp_path):
    """A five-axis program with G64 P corners turning C: the rewrite and its estimate are the
    CLI's, read back it has the input's end points and no feed above the input's, and the
    program to run is never slower than the input on the controller model."""
    text = (
        "; XYZAC\nG21 G90 G94\nG64 P0.01\nG1 X5 Y0 F2000\nG1 X7 Y0 C10\n"
        "G1 X10 Y5 F2000\nG1 X12 Y5 C20\nG1 X0 Y0 A30 C0 F1200\nM2\n"
    )
    f = tmp_path / "five.ngc"
    f.write_text(text)
    out, rw = tmp_path / "out.ngc", tmp_path / "rw.ngc"
    js = json.loads(
        cli("optimize", f, "--machine", "linuxcnc-time", "-o", out, "--rewrite", rw, "--json").stdout
    )
    for program in (text, f):
        r = millpath.optimize(program, machine="linuxcnc-time")
        assert r["text"] == out.read_text()
        assert r["rewrite"] == rw.read_text()
        assert r["before_s"] == js["before"]["cycle_time_s"]
        assert r["after_s"] == js["after"]["cycle_time_s"]
        assert r["rewritten_blocks"] == js["rewritten_blocks"] == 5
    a = millpath.estimate(text, machine="linuxcnc-time", dialect="linuxcnc")
    b = millpath.estimate(r["rewrite"], machine="linuxcnc-time", dialect="linuxcnc")
    np.testing.assert_allclose(a.toolpath.points, b.toolpath.points, atol=1e-9)
    assert (b.toolpath.feeds <= a.toolpath.feeds * (1 + 1e-9)).all()
    kept = millpath.estimate(r["text"], machine="linuxcnc-time", dialect="linuxcnc")
    assert kept.cycle_time_s <= a.cycle_time_s + 1e-9
    with pytest.raises(millpath.InputError, match="line"):
        millpath.optimize("G21\n#1=0\no1 while [#1 LT 2]\nG1 X#1 F100\n#1=[#1+1]\no1 endwhile\nM2\n")


def test_estimate_subroutines_and_tool_table_equal_cli(tmp_path):
    """A program calling a subroutine file, with a tool table: the text and the file give the
    CLI's time and blocks; the called squares are in the toolpath, offset by the tool's Z."""
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "square.ngc").write_text(
        "o<square> sub\nG1 X#1 Y0\nG1 Y#1\nG1 X0\nG1 Y0\no<square> endsub\n"
    )
    text = (
        "G21 G90 G64 P0.01\nT1 M6 G43\nG0 Z1\nG1 Z-1 F300\n#1=0\no1 repeat [3]\n"
        "#1=[#1+10]\no<square> call [#1]\no1 endrepeat\nG0 Z5\nM2\n"
    )
    prog = tmp_path / "called.ngc"
    prog.write_text(text)
    table = tmp_path / "tool.tbl"
    table.write_text("T1 P1 Z25 D6 ;6 mm end mill\n")
    run = cli("estimate", prog, "--json", "--subroutine-path", tmp_path / "lib",
              "--tool-table", table)
    js = json.loads(run.stdout)
    # The dialect found, and why, as the CLI's note says it (the file's extension counts too).
    e = millpath.estimate(prog, subroutine_path=[tmp_path / "lib"], tool_table=table)
    assert e.dialect == "linuxcnc" and "o1 repeat" in e.dialect_reason
    assert f"note: dialect linuxcnc: {e.dialect_reason}" in run.stderr
    assert millpath.estimate(prog, dialect="linuxcnc", subroutine_path=[tmp_path / "lib"],
                             tool_table=table).dialect_reason == "named"
    for program in (text, prog):
        e = millpath.estimate(program, subroutine_path=[tmp_path / "lib"], tool_table=table)
        assert e.cycle_time_s == js["cycle_time_s"]
        assert e.blocks == js["blocks"]
        assert e.violations == 0
        pts = e.toolpath.points
        # The three squares (10, 20, 30 mm), cut at Z -1 + 25 (the tool length).
        assert np.isclose(pts[:, 0].max(), 30.0) and np.isclose(pts[:, 1].max(), 30.0)
        assert np.isclose(pts[1:, 2].min(), 24.0)  # row 0: the start, before any move
    with pytest.raises(millpath.InputError, match="square"):
        millpath.estimate(text, tool_table=table)
    with pytest.raises(millpath.InputError, match="nowhere"):
        millpath.estimate(text, subroutine_path=[tmp_path / "nowhere"])
    assert millpath.estimate(prog, subroutine_path=[tmp_path / "lib"], tool_table=table,
                             verify=False).violations is None


def test_read_outline_equals_list():
    pockets = millpath.read_outline(T_PART)
    lines = cli("pocket", T_PART, "--list").stdout.strip().splitlines()
    assert len(pockets) == len(lines) >= 1
    for p, line in zip(pockets, lines):
        assert line.startswith(f"pocket {p.index}: area {p.area_mm2:.3f} mm², {len(p.islands)} islands")
        assert p.outer.shape[1] == 3
        assert p.outer[:, 0].min() == pytest.approx(float(line.split("bounds (")[1].split(",")[0]), abs=1e-3)
    # Reading the vertices back (with their bulges) gives the same pocket.
    again = millpath.read_outline([pockets[0].outer, *pockets[0].islands])
    assert again[0].area_mm2 == pytest.approx(pockets[0].area_mm2, rel=1e-9)
    with pytest.raises(millpath.InputError, match="drawing units"):
        millpath.read_outline(T_PART, drawing_units="furlong")


def test_verify_equals_cli(tmp_path):
    r = millpath.pocket("sample:aerospace", **POCKET_ARGS)
    f = tmp_path / "p.ngc"
    f.write_text(r.gcode)
    v = millpath.verify(f, "sample:aerospace", tool_diameter=12.7, machine="hsm")
    js = json.loads(cli("verify", f, "--outline", "sample:aerospace", "--tool-diameter", "12.7",
                        "--machine", "hsm", "--json").stdout)
    js.pop("pictures")
    assert v.report == js and v.passed
    t = v.report["timing"]
    assert t["machine"] == "hsm" and 0 < t["air_time_s"] < t["cycle_time_s"]
    assert t["removal_rate_mm3_s"] * t["cycle_time_s"] == pytest.approx(
        v.report["verification"]["removed_mm3"], rel=1e-9)


def test_verify_reads_every_dialect_written(tmp_path):
    for dialect in ("fanuc", "sinumerik", "grbl"):
        r = millpath.pocket("sample:aerospace", dialect=dialect, cell=0.2, **POCKET_ARGS)
        v = millpath.verify(r.gcode, "sample:aerospace", tool_diameter=12.7, cell=0.2)
        assert v.passed, (dialect, v.problems)
        named = millpath.verify(r.gcode, "sample:aerospace", tool_diameter=12.7, cell=0.2,
                                dialect=dialect)
        assert named.report == v.report


def test_five_axis_equals_cli():
    d = millpath.five_axis("paper", no_baseline=True, dt=0.01)
    js = json.loads(cli("five-axis", "--case", "paper", "--no-baseline", "--json").stdout)
    assert d["report"]["total_time_s"] == js["total_time_s"]
    assert d["report"]["violations"] == js["violations"] == []
    n = len(d["t"])
    assert d["q"].shape == d["v"].shape == d["a"].shape == d["j"].shape == (n, 5)
    assert d["axes"] == js["axis_names"]
    assert d["t"][-1] == pytest.approx(js["total_time_s"], rel=1e-9)
    assert d["feed"].max() <= 30.0 * (1 + 1e-6)  # the paper's feed limit, mm/s


def test_five_axis_end_knots_equal_cli_and_are_bounded():
    d = millpath.five_axis("paper", no_baseline=True, no_deflection=True, end_knots=4, dt=0.01)
    js = json.loads(cli("five-axis", "--case", "paper", "--no-baseline", "--no-deflection",
                        "--end-knots", "4", "--json").stdout)
    assert d["report"]["total_time_s"] == js["total_time_s"]
    assert d["report"]["violations"] == []
    plain = millpath.five_axis("paper", no_baseline=True, no_deflection=True, end_knots=0,
                               dt=0.01)
    assert d["report"]["total_time_s"] < plain["report"]["total_time_s"]
    assert plain["report"]["added_poses"] == 0
    # Left to the planner (three knots at each end of the paper's case): no slower.
    auto = millpath.five_axis("paper", no_baseline=True, no_deflection=True, dt=0.01)
    assert auto["report"]["added_poses"] > 0
    assert auto["report"]["total_time_s"] < plain["report"]["total_time_s"]
    with pytest.raises(millpath.InputError, match="end-knots"):
        millpath.five_axis("paper", no_baseline=True, end_knots=100000000)


def test_five_axis_min_interval_equals_cli_and_is_bounded():
    sweep = ROOT / "crates" / "millpath" / "tests" / "data" / "five_axis" / "sweep.csv"
    d = millpath.five_axis(path=sweep, machine="xyzac-trt", no_baseline=True, dt=0.01)
    js = json.loads(cli("five-axis", str(sweep), "--machine", "xyzac-trt", "--no-baseline",
                        "--json").stdout)
    assert d["report"]["total_time_s"] == js["total_time_s"]
    assert d["report"]["merged_poses"] == js["merged_poses"] > 0
    every = millpath.five_axis(path=sweep, machine="xyzac-trt", no_baseline=True,
                               min_interval=0.0, dt=0.01)
    assert every["report"]["merged_poses"] == 0
    assert every["report"]["intervals"] == 199
    with pytest.raises(millpath.InputError, match="min-interval"):
        millpath.five_axis(path=sweep, machine="xyzac-trt", min_interval=-1.0)


def test_five_axis_tilt_tolerance_equals_cli_and_is_bounded(tmp_path):
    """A sweep passing 0.5 degrees beside the pole: within a 1 degree tilt tolerance the axes
    are moved to pass it (one window reported), and the plan runs close to its length / feed
    (3.33 s) instead of several times it."""
    import math
    path = tmp_path / "beside.csv"
    c = 1 / math.sqrt(2)
    e = math.radians(0.5)
    rows = ["# unit: mm", "x,y,z,i,j,k"]
    for k in range(200):
        u = k / 199
        t = math.radians(-30 + 60 * u)
        v = [math.sin(t) * c - math.sin(e) * c * math.cos(t),
             math.sin(t) * c + math.sin(e) * c * math.cos(t), math.cos(t) * math.cos(e)]
        n = math.sqrt(sum(x * x for x in v))
        rows.append(f"{-50 + 100 * u:.6f},0,0,{v[0] / n:.6f},{v[1] / n:.6f},{v[2] / n:.6f}")
    path.write_text("\n".join(rows) + "\n")
    d = millpath.five_axis(path=path, machine="xyzac-trt", no_baseline=True, tilt_tolerance=1.0,
                           dt=0.01)
    js = json.loads(cli("five-axis", str(path), "--machine", "xyzac-trt", "--no-baseline",
                        "--tilt-tolerance", "1", "--json").stdout)
    assert d["report"]["total_time_s"] == js["total_time_s"] < 1.1 * 100 / 30
    assert len(d["report"]["pole_windows"]) == 1
    assert d["report"]["pole_windows"][0]["max_axis_change_rad"] <= math.radians(1.0) + 1e-12
    plain = millpath.five_axis(path=path, machine="xyzac-trt", no_baseline=True, dt=0.01)
    assert plain["report"]["pole_windows"] == []
    assert plain["report"]["total_time_s"] > 2 * 100 / 30
    with pytest.raises(millpath.InputError, match="tilt-tolerance"):
        millpath.five_axis(path=path, machine="xyzac-trt", tilt_tolerance=20.0)


def test_machines_equal_cli():
    assert millpath.machines() == json.loads(cli("machines", "--json").stdout)


def test_threads_plan_in_parallel_with_the_same_results():
    serial = [millpath.pocket("sample:aerospace", strategy=s, **POCKET_ARGS).gcode
              for s in ("offset", "zigzag")]
    out = {}

    def work(s):
        out[s] = millpath.pocket("sample:aerospace", strategy=s, **POCKET_ARGS).gcode

    ts = [threading.Thread(target=work, args=(s,)) for s in ("offset", "zigzag")]
    for t in ts:
        t.start()
    for t in ts:
        t.join()
    assert [out["offset"], out["zigzag"]] == serial


def test_readme_example_runs(tmp_path):
    """The README's example (examples/python/compare_strategies.py) runs, prints the three
    cycle times millpath.pocket gives, and writes its plot."""
    import sys

    plot = tmp_path / "feed.png"
    r = subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "compare_strategies.py"),
                        str(T_PART), str(plot)], capture_output=True, text=True, cwd=ROOT)
    assert r.returncode == 0, r.stderr
    for s in ("spiral", "offset", "zigzag"):
        t = millpath.pocket(T_PART, strategy=s, tool_diameter=4, depth=2, step_down=2).cycle_time_s
        assert f"{s:7s} cycle time {t:6.2f} s" in r.stdout
    assert plot.stat().st_size > 10_000 and plot.read_bytes()[:4] == b"\x89PNG"


def test_missing_files_are_named():
    for call in (lambda: millpath.estimate("no/such/part.ngc"),
                 lambda: millpath.verify("missing.ngc", "sample:aerospace"),
                 lambda: millpath.contour("missing.csv"),
                 lambda: millpath.pocket("missing.dxf")):
        with pytest.raises(millpath.InputError, match="missing|no/such"):
            call()


JOB = """
drawing = "{drawing}"
machine = "hsm"
[stock]
thickness = 3.0
[[tool]]
number = 2
diameter = 6.0
feed = 1200
spindle = 12000
[[operation]]
type = "profile"
tool = 2
select = "3"
step_down = 3.0
tabs = 2
"""


def test_job_equals_cli(tmp_path):
    job = tmp_path / "part.toml"
    job.write_text(JOB.format(drawing=T_PART))
    ngc, rep = tmp_path / "cli.ngc", tmp_path / "cli.json"
    cli("job", job, "-o", ngc, "--report", rep)
    r = millpath.job(job)
    assert r.gcode.encode() == ngc.read_bytes()
    report = json.loads(rep.read_text())
    assert r.report == report
    assert r.cycle_time_s == report["cycle_time_s"] > 0
    assert report["check"][-1] == ["verdict", "the drawn part, held by its tabs"]
    assert len(r.toolpath.points) > 10
    # The program the CLI wrote passes `verify --job`.
    assert cli("verify", ngc, "--job", job).returncode == 0
    with pytest.raises(millpath.InputError, match="unknown key = tabz"):
        bad = tmp_path / "bad.toml"
        bad.write_text(JOB.format(drawing=T_PART).replace("tabs = 2", "tabz = 2"))
        millpath.job(bad)


def test_job_init_equals_cli(tmp_path):
    out = tmp_path / "t.toml"
    cli("job", "--init", T_PART, "-o", out)
    assert millpath.job_init(T_PART, out) == out.read_text()
