# llvm-symbolizer output (blocks of function/file:line frames, innermost first, separated by
# blank lines) on stdin -> the outermost frame's source file per address, paths shortened.
import re, sys
for block in sys.stdin.read().split('\n\n'):
    lines = block.strip().split('\n')
    if not lines or not lines[0]:
        continue
    f = lines[-1]
    f = re.sub(r'.*/\.cargo/registry/src/[^/]*/', '', f)
    f = re.sub(r'/rustc/[0-9a-f]*/', 'rust/', f)
    f = re.sub(r'.*/(crates/millpath/)', r'\1', f)
    f = re.sub(r'.*/(fuzz/)', r'\1', f)
    print(re.sub(r':\d+:\d+$', '', f))
