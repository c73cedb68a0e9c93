"""fognav: closed-loop humanoid navigation from Python."""
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union
import os

import numpy as np
import numpy.typing as npt

from . import perception as perception

UNKNOWN: int
FLOOR: int
STAIRS: int
BORDER: int
TUNNEL: int
OBSTACLE: int
CELL_TYPES: List[str]  # names by type code
MOVES: List[str]  # "none", "walk", "sidestep", "turn", "stairs_up", "stairs_down", "crawl"
HEADINGS: List[float]  # the planner's 16 lattice headings, radians

Pose = Tuple[float, float, float]  # x, y (metres), yaw (radians)
Params = Mapping[str, Union[float, int, bool]]  # "section.key": value, as --set takes them
PathLike = Union[str, "os.PathLike[str]"]

class InputError(ValueError):
    """A bad scenario or parameter; the message names the file, line and key."""
class OutputError(OSError):
    """An output file or folder that cannot be written."""
class SimError(RuntimeError):
    """The simulator could not run (no OSMesa context, a MuJoCo error)."""

class Scenario:
    """A validated scenario file."""
    name: str
    description: str
    source: str
    seed: int
    start: Pose
    goal: Tuple[float, float]
    goal_tolerance: float
    params: Dict[str, float]
    max_cycles: int
    max_steps: int
    def summary(self) -> str: ...

def load_scenario(path: PathLike) -> Scenario:
    """Reads and validates a scenario as `fognav validate` does (InputError otherwise)."""

def run(scenario: Union[Scenario, PathLike], out: Optional[PathLike] = None,
        params: Optional[Params] = None, seed: Optional[int] = None) -> Dict[str, Any]:
    """Runs a whole mission as `fognav run`; returns report.json as a dict."""

def param_defaults() -> Dict[str, float]:
    """Every tunable's default by "section.key"."""

class Mission:
    """A mission stepped from Python."""
    cycles: int
    def __init__(self, scenario: Union[Scenario, PathLike], params: Optional[Params] = None,
                 seed: Optional[int] = None, out: Optional[PathLike] = None) -> None: ...
    def look_around(self) -> None: ...
    def look(self, pan: float, tilt: float) -> Dict[str, Any]:
        """left, right, depth, depth_true, points_camera, points_grid, labels, planes,
        labelled_grid, labelled_heights, camera_pose, camera_pose_true, robot_pose,
        intrinsics."""
    def fog(self) -> Dict[str, Any]:
        """types, heights, ceiling, headroom_seen, walked, origin, resolution."""
    def plan(self, goal: Optional[Tuple[float, float]] = None) -> Dict[str, Any]:
        """status, reason, reaches_goal, cost, length, poses, moves, postures, floor_z, runs."""
    def execute(self, path: Mapping[str, Any]) -> Dict[str, Any]:
        """blocked_at, reached, steps, collisions, ended."""
    def step(self) -> bool:
        """One cycle with the built-in decisions; False once the mission has ended."""
    def believed_pose(self) -> Pose: ...
    def true_pose(self) -> Pose: ...
    def done(self) -> bool: ...
    def report(self) -> Dict[str, Any]: ...
