#!/usr/bin/env python3
"""Cycle times of the `linuxcnc` controller model against LinuxCNC 2.9 itself.

Usage (from the repository root, after `cargo build --release`):

    tools/linuxcnc_compare.py extract OUT_DIR          # LinuxCNC's test programs, from the mirror
    tools/linuxcnc_compare.py pockets OUT_DIR          # millpath's pocket programs
    tools/linuxcnc_compare.py run OUT.csv FILE.ngc...  # both times per program (2 LinuxCNC runs at a time)
    tools/linuxcnc_compare.py report OUT.csv           # the BENCHMARKS.md table and summary

`extract` copies `nc_files/` and `tests/trajectory-planner/circular-arcs/nc_files/` of LinuxCNC
commit f1270d6ed7 from the git mirror (`/work/.mirror/LinuxCNC+linuxcnc/repo`, or $LCNC_REPO)
into OUT_DIR; nothing of LinuxCNC is committed here. `run` first times each program with
`millpath estimate --machine linuxcnc-time` (programs millpath refuses are listed as such),
then runs `../shared/tools/linuxcnc-time/linuxcnc-time FILE 500 2000` with a 90 s limit
(LCNC_TIMEOUT) on the others, skipping programs the model times above 120 s; LinuxCNC's
refusals and time-outs are listed as such. Rows: program,linuxcnc_s,status (the LinuxCNC
times, recorded once). `report` times every program again with the current millpath build.
"""
import csv, os, subprocess, sys, concurrent.futures as cf

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MILLPATH = os.path.join(ROOT, "target", "release", "millpath")
LCNC = os.path.normpath(os.path.join(ROOT, "..", "shared", "tools", "linuxcnc-time", "linuxcnc-time"))
REPO = os.environ.get("LCNC_REPO", "/work/.mirror/LinuxCNC+linuxcnc/repo")
COMMIT = "f1270d6ed7"
DIRS = ["nc_files", "tests/trajectory-planner/circular-arcs/nc_files"]


def extract(out):
    names = subprocess.run(["git", "-C", REPO, "ls-tree", "-r", "--name-only", COMMIT, "--"] + DIRS,
                           capture_output=True, text=True, check=True).stdout.split()
    n = 0
    for name in names:
        if not name.lower().endswith(".ngc"):
            continue
        data = subprocess.run(["git", "-C", REPO, "show", f"{COMMIT}:{name}"], capture_output=True, check=True).stdout
        dest = os.path.join(out, name.replace("/", "__"))
        os.makedirs(out, exist_ok=True)
        with open(dest, "wb") as f:
            f.write(data)
        n += 1
    print(f"{n} programs in {out}")


def pockets(out):
    """The aerospace pocket, one 5 mm level, 12.7 mm tool, 40 % stepover, 600 in/min, by each
    strategy (and the spiral as arcs), in each path mode: as written (no mode: LinuxCNC's
    default G64), `G64 P0.01` and `G61`."""
    os.makedirs(out, exist_ok=True)
    for s in ["spiral", "offset", "zigzag"]:
        for arcs in ([], ["--arcs"]) if s == "spiral" else ([],):
            base = os.path.join(out, "tmp.ngc")
            subprocess.run([MILLPATH, "pocket", "sample:aerospace", "--strategy", s, "--tool-diameter", "12.7",
                            "--stepover", "0.4", "--depth", "5", "--step-down", "5", "--feed", "600ipm",
                            "-o", base] + arcs, check=True, capture_output=True)
            lines = open(base).read().splitlines()
            os.remove(base)
            at = next(i for i, l in enumerate(lines) if l.startswith("G54")) + 1
            for mode, code in [("g64", None), ("p01", "G64 P0.01"), ("g61", "G61")]:
                text = lines[:at] + ([code] if code else []) + lines[at:]
                name = f"pocket_{s}{'_arcs' if arcs else ''}_{mode}.ngc"
                open(os.path.join(out, name), "w").write("\n".join(text) + "\n")
    print(f"pocket programs in {out}")


def model_time(path):
    r = subprocess.run([MILLPATH, "estimate", path, "--machine", "linuxcnc-time", "--json"],
                       capture_output=True, text=True)
    if r.returncode != 0:
        return None, (r.stderr.strip().splitlines() or ["?"])[-1]
    import json
    return json.loads(r.stdout)["cycle_time_s"], ""


def lcnc_time(path):
    env = dict(os.environ, LCNC_TIMEOUT=os.environ.get("LCNC_TIMEOUT", "90"))
    r = subprocess.run([LCNC, path, "500", "2000"], capture_output=True, text=True, env=env)
    if r.returncode != 0:
        return None, (r.stderr.strip().splitlines() or ["?"])[-1]
    t = float(r.stdout.strip())
    if t <= 0:
        # Seen once in a run of two side by side: no motion recorded at all.
        return None, "no motion time recorded"
    return t, ""


def run(out, files):
    done = set()
    if os.path.exists(out):
        done = {row["program"] for row in csv.DictReader(open(out))}
    todo = []
    for f in files:
        if f in done:
            continue
        m, why = model_time(f)
        if m is None:
            write(out, [f, "", "millpath refuses: " + why.replace(",", ";")])
        elif m > 120:
            write(out, [f, "", "skipped: model time > 120 s"])
        elif m == 0:
            write(out, [f, "", "skipped: no motion"])
        else:
            todo.append(f)
    with cf.ThreadPoolExecutor(max_workers=2) as ex:
        futs = {ex.submit(lcnc_time, f): f for f in todo}
        for fut in cf.as_completed(futs):
            f = futs[fut]
            t, why = fut.result()
            status = "ok" if t is not None else "linuxcnc: " + why.replace(",", ";")
            write(out, [f, "" if t is None else f"{t:.4f}", status])


def write(out, row):
    new = not os.path.exists(out)
    with open(out, "a", newline="") as f:
        w = csv.writer(f)
        if new:
            w.writerow(["program", "linuxcnc_s", "status"])
        w.writerow(row)
        f.flush()


def report(path):
    rows = [r for r in csv.DictReader(open(path)) if r["status"] == "ok"]
    errs = []
    print("| program | LinuxCNC (s) | linuxcnc model (s) | error |")
    print("|---|---|---|---|")
    for r in sorted(rows, key=lambda r: os.path.basename(r["program"])):
        t = float(r["linuxcnc_s"])
        m, why = model_time(r["program"])
        if m is None:
            print(f"| {os.path.basename(r['program'])} | {t:.3f} | refused: {why} | |")
            continue
        e = (m - t) / t * 100 if t > 0 else 0.0
        errs.append((abs(e), os.path.basename(r["program"])))
        print(f"| {os.path.basename(r['program'])} | {t:.3f} | {m:.3f} | {e:+.1f} % |")
    n = len(errs)
    if n:
        within = sum(e <= 5 for e, _ in errs)
        print(f"\n{n} programs: {within} ({100 * within / n:.1f} %) within 5 %, mean |error| "
              f"{sum(e for e, _ in errs) / n:.2f} %, max {max(errs)[0]:.1f} % ({max(errs)[1]}), "
              f"beyond 10 %: {sum(e > 10 for e, _ in errs)}")
    others = [r for r in csv.DictReader(open(path)) if r["status"] != "ok"]
    for r in others:
        print(f"not compared: {os.path.basename(r['program'])}: {r['status']}")


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "extract":
        extract(sys.argv[2])
    elif cmd == "pockets":
        pockets(sys.argv[2])
    elif cmd == "run":
        run(sys.argv[2], sys.argv[3:])
    elif cmd == "report":
        report(sys.argv[2])
    else:
        print(__doc__)
        sys.exit(2)
