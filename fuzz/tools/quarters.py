#!/usr/bin/env python3
"""Coverage over a libFuzzer run, for the stopping rule (fuzz/README.md, "When a target is flat").

usage: quarters.py LOG [TOTAL_SECONDS]

Reads the status lines of a plain run (`#N  NEW  cov: C ...`; the run's progress is its
executions, out of `stat::number_of_executed_units` or the last N) or of a fork run
(`#N: cov: C ... time: Ts`; progress is time, out of TOTAL_SECONDS, default the last line's),
ignores those before INITED (the corpus re-run), and prints `cov` at 25/50/75/90/100 % of the
run, the coverage at the start, the growth in the last quarter (edges and per cent) and each
increase with where in the run it came."""
import re, sys

log = open(sys.argv[1], errors="replace").read().splitlines()
pts = []  # (progress: seconds in fork mode, executions in plain mode, cov)
inited = False
start_cov = None
fork = False
total_execs = None
for line in log:
    m = re.match(r"stat::number_of_executed_units: (\d+)", line)
    if m:
        total_execs = int(m.group(1))
    m = re.match(r"#(\d+):\s+cov: (\d+) .*time: (\d+)s", line)  # fork mode
    if m:
        t, c = float(m.group(3)), int(m.group(2))
        fork = True
        if start_cov is None:
            start_cov = c
        pts.append((t, c))
        continue
    m = re.match(r"#(\d+)\s+(\w+)\s+cov: (\d+) ", line)  # plain mode
    if m:
        n, kind, c = int(m.group(1)), m.group(2), int(m.group(3))
        if kind == "INITED":
            inited, start_cov = True, c
            pts.append((0.0, c))
            continue
        if inited:
            pts.append((float(n), c))
if not pts:
    sys.exit("no status lines")
if fork:
    total = float(sys.argv[2]) if len(sys.argv) > 2 else pts[-1][0]
else:
    total = float(total_execs or pts[-1][0])
unit = "s" if fork else "executions"

def cov_at(frac):
    best = start_cov
    for t, c in pts:
        if t <= frac * total:
            best = c
    return best

qs = [cov_at(f) for f in (0.25, 0.5, 0.75, 0.9, 1.0)]
print(f"start {start_cov}; at 25/50/75/90/100 %: {' / '.join(map(str, qs))} (of {total:.0f} {unit})")
q3 = cov_at(0.75)
print(f"last quarter: +{qs[-1] - q3} edges ({100 * (qs[-1] - q3) / max(q3, 1):.2f} %)")
prev = start_cov
for t, c in pts:
    if c > prev:
        print(f"  {t:12.0f} {unit} ({100 * t / total:5.1f} %): {prev} -> {c}")
        prev = c
