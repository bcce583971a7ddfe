"""Type stubs of millpath (the functions are the `millpath` CLI's commands; keyword
arguments are the commands' flags with `_` for `-`)."""

import os
from typing import Any, Dict, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

PathLike = Union[str, "os.PathLike[str]"]
Points = npt.ArrayLike
Outline = Union[PathLike, Points, Sequence[Points]]

class InputError(ValueError):
    """Bad input: the message names the value, where it came from and what is expected."""

class InternalError(RuntimeError):
    """An internal fault of the engine: a bug to report."""

class Toolpath:
    """A planned toolpath, mm and mm/s."""
    @property
    def points(self) -> npt.NDArray[np.float64]:
        """(N + 1) x 3: the start, then the end of each move."""
    @property
    def feeds(self) -> npt.NDArray[np.float64]:
        """N programmed feeds, mm/s (NaN for rapids)."""
    @property
    def rapid(self) -> npt.NDArray[np.bool_]:
        """N flags: the move is a rapid."""
    @property
    def cut_length_mm(self) -> float: ...
    @property
    def rapid_length_mm(self) -> float: ...
    @property
    def levels(self) -> int: ...
    def trajectory(self, machine: str = "hsm", dt: float = 0.01) -> Dict[str, npt.NDArray[np.float64]]:
        """Planned on `machine`, sampled every `dt` s: t, s, feed (N); position, velocity,
        acceleration, jerk (N x 3)."""
    def __len__(self) -> int: ...

class PocketResult:
    gcode: str
    """Byte for byte the file `millpath pocket ... -o FILE` writes."""
    cycle_time_s: float
    strategy: str
    report: Dict[str, Any]
    """The `--report` JSON."""
    toolpath: Toolpath
    note: Optional[str]

class DrillResult:
    gcode: str
    """Byte for byte the file `millpath drill ... -o FILE` writes."""
    cycle_time_s: float
    report: Dict[str, Any]
    """The `--report` JSON."""
    toolpath: Toolpath
    holes: npt.NDArray[np.float64]
    """The holes cut, in cutting order: N x 3 (x, y, diameter), mm."""
    note: Optional[str]

class ProfileResult:
    gcode: str
    """Byte for byte the file `millpath profile ... -o FILE` writes."""
    cycle_time_s: float
    report: Dict[str, Any]
    """The `--report` JSON: outlines, tabs, the dense check, the bridge verdict."""
    toolpath: Toolpath
    notes: List[str]

class JobResult:
    gcode: str
    """Byte for byte the file `millpath job FILE -o OUT` writes."""
    cycle_time_s: float
    """Of the written program on the machine, tool changes included, s."""
    report: Dict[str, Any]
    """The `--report` JSON: tools, operations (tool, cut, time, checks), the stock check."""
    toolpath: Toolpath
    """Every operation's toolpath joined."""
    notes: List[str]

class ContourResult:
    gcode: str
    cycle_time_s: float
    report: Dict[str, Any]
    toolpath: Toolpath
    warnings: List[str]

class VerifyResult:
    passed: bool
    problems: List[str]
    report: Dict[str, Any]
    toolpath: Toolpath

class Estimate:
    cycle_time_s: float
    machine: str
    blocks: int
    violations: Optional[int]
    """Samples over a limit; None when the verifier did not run."""
    toolpath: Toolpath

class Pocket:
    index: int
    outer: npt.NDArray[np.float64]
    """N x 3: x, y, bulge of the span leaving each vertex."""
    islands: List[npt.NDArray[np.float64]]
    area_mm2: float

def pocket(
    outline: Outline,
    *,
    strategy: str = "spiral",
    tool_diameter: float = 12.7,
    flute_length: Optional[float] = None,
    stepover: Union[None, str, float] = None,
    depth: float = 25.0,
    step_down: Optional[float] = None,
    wall_stock: float = 0.0,
    floor_stock: float = 0.0,
    conventional: bool = False,
    entry: str = "helix",
    helix_radius: Optional[float] = None,
    ramp_angle: float = 3.0,
    safe_height: float = 1.0,
    clearance_height: float = 5.0,
    feed: Union[str, float] = "600ipm",
    slowdown: float = 0.75,
    angle: float = 0.0,
    transition: Optional[float] = None,
    min_radius: float = 1.0,
    morph: Optional[str] = None,
    arcs: bool = False,
    both_ways: bool = False,
    lift: float = 0.0,
    finish: bool = False,
    no_feed_modulation: bool = False,
    machine: str = "hsm",
    cell: Optional[float] = None,
    draft: Optional[float] = None,
    bottom_outline: Optional[PathLike] = None,
    tolerance: Optional[float] = None,
    rest_from: Optional[PathLike] = None,
    rest_from_diameter: Optional[float] = None,
    select: Union[None, str, int, Sequence[int]] = None,
    layer: Optional[str] = None,
    join_tolerance: float = 0.01,
    drawing_units: Optional[str] = None,
    dialect: str = "linuxcnc",
    units: str = "mm",
    decimals: Optional[int] = None,
    tool_number: int = 1,
    spindle: float = 10000.0,
    coolant: str = "flood",
    line_numbers: bool = False,
) -> PocketResult:
    """Rough a pocket (an outline file, `"sample:aerospace"`, an N x 2 array or a list of
    arrays: boundary and islands) as `millpath pocket` does. With `rest_from` (a previous
    program, ours or another CAM's; its tool's diameter from `rest_from_diameter` or our
    header), cut only what it left within this tool's reach, as `millpath pocket
    --rest-from` does: strategy `"rest"`, its figures as the report. `stepover` and
    `step_down` default as the command's do: 0.4 and half the diameter (at most the flute
    length), and for `"adaptive"` 0.1 and the flute length (3 x the diameter where it is not
    given)."""

def drill(
    drawing: PathLike,
    *,
    tool_diameter: float = 6.0,
    depth: float = 10.0,
    through: bool = False,
    breakthrough: float = 1.0,
    min_diameter: Optional[float] = None,
    max_diameter: Optional[float] = None,
    peck: Optional[float] = None,
    chip_break: Optional[float] = None,
    dwell: Optional[float] = None,
    retract: float = 1.0,
    clearance_height: float = 5.0,
    stay_at_retract: bool = False,
    feed: Union[str, float] = "200",
    bore_feed: Union[str, float] = "800",
    pitch: float = 1.0,
    conventional: bool = False,
    stepover: float = 0.5,
    finish_allowance: float = 0.1,
    tolerance: float = 0.01,
    diameter_tolerance: float = 0.01,
    drill_only: bool = False,
    machine: str = "hsm",
    layer: Optional[str] = None,
    join_tolerance: float = 0.01,
    drawing_units: Optional[str] = None,
    dialect: str = "linuxcnc",
    units: str = "mm",
    decimals: Optional[int] = None,
    tool_number: int = 1,
    spindle: float = 10000.0,
    coolant: str = "flood",
    line_numbers: bool = False,
) -> DrillResult:
    """Drill (canned cycles) and helix-bore the circles of a drawing (`.dxf`, `.svg`,
    `.json`) as `millpath drill` does."""

def contour(
    points: Union[PathLike, Points, None] = None,
    *,
    sample: bool = False,
    tool_diameter: Optional[float] = None,
    tolerance: Optional[float] = None,
    side: str = "inside",
    depth: Optional[float] = None,
    step_down: Optional[float] = None,
    finish_allowance: float = 0.2,
    curve: str = "four-point",
    arcs: bool = False,
    feed: float = 1000.0,
    plunge_feed: float = 300.0,
    safe_height: float = 10.0,
    clearance_height: float = 2.0,
    lead_radius: float = 2.0,
    machine: str = "hsm",
    dialect: str = "linuxcnc",
    units: str = "mm",
    decimals: Optional[int] = None,
    tool_number: int = 1,
    spindle: float = 10000.0,
    coolant: str = "flood",
    line_numbers: bool = False,
) -> ContourResult:
    """A free-form contour through points, as `millpath contour` makes it."""

def profile(
    drawing: Union[PathLike, Points, Sequence[Points], None] = None,
    *,
    sample: bool = False,
    layer: Optional[str] = None,
    join_tolerance: float = 0.01,
    drawing_units: Optional[str] = None,
    side: str = "auto",
    tool_diameter: Optional[float] = None,
    depth: Optional[float] = None,
    stock_thickness: Optional[float] = None,
    step_down: Optional[float] = None,
    stock_to_leave: Optional[float] = None,
    conventional: bool = False,
    lead_radius: float = 2.0,
    entry: str = "ramp",
    helix_radius: float = 2.0,
    ramp_angle: float = 3.0,
    tolerance: Optional[float] = None,
    feed: Union[str, float] = "1000",
    plunge_feed: float = 300.0,
    safe_height: float = 10.0,
    clearance_height: float = 2.0,
    tabs: Union[str, int] = "0",
    tab_width: float = 6.0,
    tab_height: float = 2.0,
    tab_shape: str = "square",
    machine: str = "hsm",
    dialect: str = "linuxcnc",
    units: str = "mm",
    decimals: Optional[int] = None,
    tool_number: int = 1,
    spindle: float = 10000.0,
    coolant: str = "flood",
    line_numbers: bool = False,
) -> ProfileResult:
    """A drawing's outlines cut out (parts outside, holes inside, or as `side` says), with
    lead arcs, ramp or helix entries and holding tabs, as `millpath profile` does."""

def estimate(
    program: PathLike,
    machine: str = "hsm",
    dialect: str = "auto",
    *,
    subroutine_path: Optional[Sequence[PathLike]] = None,
    tool_table: Optional[PathLike] = None,
    lenient: bool = False,
    verify: bool = True,
) -> Estimate:
    """Cycle time of a G-code program (a path or its text) on a machine, as
    `millpath estimate`: subroutine files searched in the program's folder then
    `subroutine_path` (`--subroutine-path`), tool lengths from a LinuxCNC `tool_table`
    (`--tool-table`), the limit verifier run unless `verify=False`."""

def optimize(
    program: PathLike,
    machine: str = "linuxcnc-time",
    tolerance: float = 0.001,
    tolerance_deg: float = 0.001,
    merge: bool = True,
) -> dict:
    """`millpath optimize`: runs of straight blocks within `tolerance` mm (`tolerance_deg`
    for the rotary axes) of one chord merged, then the straight feed blocks rewritten in
    inverse time at what the machine's joints allow, kept only when the controller model
    runs it faster. Keys: `text`, `rewrite`, `before_s`, `after_s`, `rewritten_blocks`,
    `merged_blocks`, `kept_rewrite`, `outcome`."""

def verify(
    program: PathLike,
    outline: Outline,
    *,
    tool_diameter: Optional[float] = None,
    wall_stock: float = 0.0,
    stepover: Union[str, float] = "0.4",
    cell: Optional[float] = None,
    decimals: Optional[int] = None,
    select: Optional[str] = None,
    dialect: str = "auto",
    layer: Optional[str] = None,
    join_tolerance: float = 0.01,
    drawing_units: Optional[str] = None,
) -> VerifyResult:
    """Check a program against a pocket outline by material-removal simulation; the
    program's dialect is found from its first lines unless `dialect` names it, and the tool
    from its header (millpath's programs name it) unless `tool_diameter` is given."""

def five_axis(
    case: Optional[str] = None,
    *,
    path: Optional[PathLike] = None,
    machine: str = "paper",
    feed: Optional[float] = None,
    linear_velocity: Optional[float] = None,
    linear_acceleration: Optional[float] = None,
    linear_jerk: Optional[float] = None,
    rotary_velocity: Optional[float] = None,
    rotary_acceleration: Optional[float] = None,
    rotary_jerk: Optional[float] = None,
    tool_length: Optional[float] = None,
    z1: Optional[float] = None,
    z2: Optional[float] = None,
    no_baseline: bool = False,
    no_deflection: bool = False,
    end_knots: Optional[int] = None,
    min_interval: Optional[float] = None,
    tilt_tolerance: Optional[float] = None,
    dt: float = 0.001,
) -> Dict[str, Any]:
    """Five-axis minimum-time trajectory: report dict, axes, and sampled arrays t, feed
    (N), q, v, a, j (N x 5)."""

def read_outline(
    path: Outline,
    *,
    layer: Optional[str] = None,
    join_tolerance: float = 0.01,
    drawing_units: Optional[str] = None,
) -> List[Pocket]:
    """The pockets of an outline file or sample, as `millpath pocket FILE --list` numbers them."""

def job(
    path: Union[str, "os.PathLike[str]"],
    *,
    dialect: Optional[str] = None,
    machine: Optional[str] = None,
) -> JobResult:
    """A whole part from a job file (`millpath job FILE`); `dialect` and `machine` override
    the file's."""

def job_init(
    drawing: Union[str, "os.PathLike[str]"],
    output: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    dialect: str = "linuxcnc",
    machine: str = "hsm",
    layer: Optional[str] = None,
    join_tolerance: float = 0.01,
    drawing_units: Optional[str] = None,
) -> str:
    """The starting job file `millpath job --init DRAWING -o OUTPUT` writes (nothing is
    written: `output` only decides how the file names the drawing)."""

def machines() -> List[Dict[str, Any]]:
    """The built-in machine presets (as `millpath machines --json`)."""
