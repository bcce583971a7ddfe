#!/usr/bin/env python3
"""When and where a plain libFuzzer run (-print_pcs=1) found each new PC after start-up.

usage: pc_timeline.py LOG MAPS BINARY

MAPS is a copy of /proc/PID/maps taken while the run was going (it gives the load address).
Each NEW_PC after INITED gets the execution count of the status line before it, as a fraction
of the run's `stat::number_of_executed_units`, and the outermost frame of its symbolized
location outside the fuzz target (tools/outermost.py's shortening)."""
import re, subprocess, sys, os

log, maps, binary = sys.argv[1:4]
here = os.path.dirname(os.path.abspath(__file__))
real = os.path.realpath(binary)
base = None
for line in open(maps):
    if line.rstrip().endswith(real) or line.rstrip().endswith(binary):
        base = int(line.split("-")[0], 16)
        break
if base is None:
    sys.exit("binary not in maps")
inited, n, total = False, 0, None
found = []  # (execs, pc)
for line in open(log, errors="replace"):
    if "INITED" in line:
        inited = True
    m = re.match(r"#(\d+)\s", line)
    if m:
        n = int(m.group(1))
    m = re.match(r"stat::number_of_executed_units: (\d+)", line)
    if m:
        total = int(m.group(1))
    m = re.match(r"\s*NEW_PC: (0x[0-9a-f]+)", line)
    if m and inited:
        found.append((n, int(m.group(1), 16) - base))
if not found:
    print("no new PCs after INITED")
    sys.exit()
total = total or n
sym = subprocess.run(["llvm-symbolizer", f"--obj={binary}"], capture_output=True, text=True,
                     input="".join(f"0x{a:x}\n" for _, a in found)).stdout
blocks = [b for b in sym.split("\n\n") if b.strip()]
for (k, a), b in zip(found, blocks):
    frames = b.strip().split("\n")
    pairs = list(zip(frames[0::2], frames[1::2]))  # (function, file:line), innermost first
    outer = [p for p in pairs if "fuzz/" not in p[1] and "libfuzzer" not in p[1]]
    fn, loc = (outer[-1] if outer else pairs[-1])
    loc = re.sub(r".*/\.cargo/registry/src/[^/]*/", "", loc)
    loc = re.sub(r"/rustc/[0-9a-f]*/", "rust/", loc)
    loc = re.sub(r".*/(crates/millpath/)", r"\1", loc)
    print(f"{100 * k / total:5.1f} %  {k:>11}  {fn[:60]:60}  {loc}")
