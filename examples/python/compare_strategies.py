"""Pocket a drawing with each of millpath's three strategies, compare their cycle times, and
plot the feed the machine achieves along each path.

    python examples/python/compare_strategies.py [DRAWING] [PLOT.png]

DRAWING defaults to a real part drawing in ../shared/real-inputs/files (run from the clone).
"""

import sys

import matplotlib

matplotlib.use("Agg")  # write a file; no window needed
import matplotlib.pyplot as plt
import numpy as np

import millpath

drawing = sys.argv[1] if len(sys.argv) > 1 else "../shared/real-inputs/files/lc_t-part.dxf"
plot = sys.argv[2] if len(sys.argv) > 2 else "feed_along_path.png"

results = {}
for strategy in ("spiral", "offset", "zigzag"):
    r = millpath.pocket(drawing, strategy=strategy, tool_diameter=4, depth=2, step_down=2,
                        machine="hsm")
    results[strategy] = r
    print(f"{strategy:7s} cycle time {r.cycle_time_s:6.2f} s, "
          f"path {r.report['path_length_mm']:7.1f} mm, "
          f"{'verified' if not r.report['problems'] else 'NOT verified'}")

fig, ax = plt.subplots(figsize=(9, 4))
for strategy, r in results.items():
    tr = r.toolpath.trajectory(machine="hsm", dt=0.005)  # numpy arrays, one row per sample
    t, feed = tr["t"], tr["feed"]
    along = np.concatenate([[0.0], np.cumsum(np.diff(t) * (feed[1:] + feed[:-1]) / 2)])
    ax.plot(along, feed * 60, lw=0.7, label=f"{strategy}: {r.cycle_time_s:.1f} s")
ax.set_xlabel("distance along the path, mm")
ax.set_ylabel("feed achieved on hsm, mm/min")
ax.legend()
fig.tight_layout()
fig.savefig(plot, dpi=120)
print(f"plot: {plot}")
