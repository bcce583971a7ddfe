#!/usr/bin/env bash
# The shape suite's strategy table of BENCHMARKS.md: every pocket × strategy × modulation on
# our planner (hsm, and LinuxCNC's limits) and on LinuxCNC 2.9's own trajectory planner.
#   tools/strategy_table.sh OUT_DIR
# Writes OUT_DIR/*.ngc, OUT_DIR/table.tsv (our planner), OUT_DIR/lcnc.tsv (LinuxCNC, two runs
# at a time, about 15 minutes) and prints the markdown table. Needs linuxcnc-uspace and
# ../shared/tools/linuxcnc-time beside the repository.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: tools/strategy_table.sh OUT_DIR}
mkdir -p "$out"
tool=$(cd .. && pwd)/shared/tools/linuxcnc-time/linuxcnc-time
cargo run --release --quiet --example strategy_table -- "$out" > "$out/table.tsv"
( cd "$out" && ls *.ngc | LCNC_TIMEOUT=300 xargs -P 2 -I{} sh -c \
    'printf "%s\t%s\n" "{}" "$('"$tool"' {} 500 2000 2>/dev/null | tail -1)"' ) > "$out/lcnc.tsv"
python3 - "$out" <<'PY'
import csv, sys, os
out = sys.argv[1]
lc = {}
for line in open(os.path.join(out, "lcnc.tsv")):
    name, t = line.rstrip("\n").split("\t")
    lc[name] = t
rows = list(csv.DictReader(open(os.path.join(out, "table.tsv")), delimiter="\t"))
print("| pocket | strategy | path mm | mean eng. ° | above nominal % | hsm s (mod / flat) | LinuxCNC model s (mod / flat) | LinuxCNC 2.9 s (mod / flat) | uncut mm² |")
print("|---|---|---|---|---|---|---|---|---|")
key = lambda r: (r["pocket"], r["strategy"])
seen = {}
for r in rows:
    seen.setdefault(key(r), {})[r["modulation"]] = r
for (pocket, strategy), m in seen.items():
    on, off = m.get("on"), m.get("off")
    if not on or not off or on.get("path_mm") is None:
        print(f"| {pocket} | {strategy} | error | | | | | | |")
        continue
    def f(mod):
        t = lc.get(f"{pocket.replace(' ', '_').replace(':', '_')}_{strategy}_{mod}.ngc", "?")
        try:
            return f"{float(t):.2f}"
        except ValueError:
            return "error"
    print(f"| {pocket} | {strategy} | {float(on['path_mm']):.0f} | {float(on['mean_engagement_deg']):.1f} | "
          f"{float(on['above_nominal_pct']):.1f} | {on['hsm_s']} / {off['hsm_s']} | "
          f"{on['linuxcnc_model_s']} / {off['linuxcnc_model_s']} | {f('on')} / {f('off')} | {on['uncut_mm2']} |")
PY
