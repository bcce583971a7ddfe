#!/bin/bash
# Where a running libFuzzer process (started with -print_pcs=1) found its new PCs, by crate:
# new_pcs.sh PID LOG. The PCs in the log are run-time addresses; the binary's load address
# comes from /proc/PID/maps, so run this while the fuzzer is still running.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
pid=$1; log=$2
bin=$(readlink "/proc/$pid/exe")
base=0x$(grep -F "$bin" "/proc/$pid/maps" | head -1 | cut -d- -f1)
grep NEW_PC "$log" | awk '{print $2}' | while read -r a; do printf "0x%x\n" $((a - base)); done |
  llvm-symbolizer --obj="$bin" | python3 "$here/outermost.py" |
  awk -F/ '{print ($1 == "crates") ? $1"/"$2"/"$3"/"$4 : $1}' | sort | uniq -c | sort -rn
