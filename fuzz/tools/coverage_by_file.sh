#!/bin/bash
# Per-file coverage of a corpus: coverage_by_file.sh BINARY OUT CORPUS_DIR...
# Writes OUT.files: covered PCs, instrumented PCs and source file, a line each. Each PC is
# attributed to the function it was compiled into (the outermost inlined frame), so a
# std or helper function inlined into millpath counts as millpath. Needs llvm-symbolizer,
# readelf and python3; the binary from `cargo fuzz build -O -s none` (debug info kept).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
b=$1; out=$2; shift 2
python3 "$here/pcs.py" "$b" > "$out.all" 2>/dev/null
rm -rf "$out.empty" "$out.ctl"; mkdir -p "$out.empty"
FUZZ_STRICT_VERIFY=1 "$b" -merge=1 -merge_control_file="$out.ctl" -rss_limit_mb=2048 -timeout=20 \
  -max_len=4096 "$out.empty" "$@" > "$out.load" 2>&1
llvm-symbolizer --obj="$b" < "$out.all" | python3 "$here/outermost.py" > "$out.src"
python3 - "$out" <<'PY'
import sys, collections
out = sys.argv[1]
src = [l.strip() for l in open(out + '.src')]
cov = set()
for l in open(out + '.ctl'):
    if l.startswith('COV '):
        cov.update(int(x) for x in l.split()[2:])
tot, hit = collections.Counter(), collections.Counter()
for i, f in enumerate(src):
    tot[f] += 1
    hit[f] += i in cov
print(f"{len(src)} pcs, {len(cov)} covered")
with open(out + '.files', 'w') as w:
    for f in sorted(tot):
        w.write(f"{hit[f]}\t{tot[f]}\t{f}\n")
PY
