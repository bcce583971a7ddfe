"""millpath: a CAM engine (adaptive spiral pockets, free-form contours, jerk-limited cycle
times, five-axis minimum-time trajectories) for Python.

Each function is the `millpath` command of the same name, its keyword arguments named as the
command's flags (``tool_diameter`` for ``--tool-diameter``)::

    import millpath
    r = millpath.pocket("sample:aerospace", strategy="spiral", depth=5, step_down=5)
    r.gcode            # the program, byte for byte what `millpath pocket ... -o` writes
    r.cycle_time_s     # its cycle time on the machine (default "hsm")
    r.report           # the JSON report as a dict
    r.toolpath.points  # (N + 1) x 3 numpy array, mm

Bad input raises :class:`InputError` (a ``ValueError``) with the message the CLI prints;
an internal fault raises :class:`InternalError`. Planning releases the GIL, so threads can
plan several parts at once.
"""

from ._millpath import (
    ContourResult,
    DrillResult,
    Estimate,
    InputError,
    InternalError,
    JobResult,
    Pocket,
    PocketResult,
    ProfileResult,
    Toolpath,
    VerifyResult,
    contour,
    drill,
    estimate,
    five_axis,
    job,
    job_init,
    machines,
    optimize,
    pocket,
    profile,
    read_outline,
    verify,
)

__all__ = [
    "ContourResult",
    "DrillResult",
    "Estimate",
    "InputError",
    "InternalError",
    "JobResult",
    "Pocket",
    "PocketResult",
    "ProfileResult",
    "Toolpath",
    "VerifyResult",
    "contour",
    "drill",
    "estimate",
    "five_axis",
    "job",
    "job_init",
    "machines",
    "optimize",
    "pocket",
    "profile",
    "read_outline",
    "verify",
]
