"""The paper's plane segmentation and maps on any range data."""
from typing import Any, Dict, Mapping, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

Params = Mapping[str, Union[float, int, bool]]
Planes = Dict[str, np.ndarray]  # normal (P, 3), d, num_points, rms, centroid (P, 3)
FogDict = Dict[str, Any]

def segment(points: npt.ArrayLike, params: Optional[Params] = None
            ) -> Tuple[npt.NDArray[np.int32], Planes]:
    """H x W x 3 points (camera frame, NaN none) -> (labels H x W, planes)."""

def depth_to_points(depth: npt.ArrayLike, fx: float, fy: float, cx: float, cy: float,
                    scale: float = 1.0) -> npt.NDArray[np.float32]:
    """H x W depth (times scale in metres; 0 or NaN none) -> H x W x 3 points."""

class Maps:
    """Occupancy grid, floor height map and FOG over the caller's frames (grid frame G)."""
    def __init__(self, params: Optional[Params] = None) -> None: ...
    def insert(self, points: npt.ArrayLike,
               labels: Union[npt.ArrayLike, Tuple[npt.ArrayLike, Planes]],
               camera_pose: npt.ArrayLike, planes: Optional[Planes] = None,
               robot_pose: Optional[Tuple[float, float, float]] = None) -> None:
        """Adds one frame; camera_pose is the 4 x 4 X_GC."""
    def fog(self) -> FogDict:
        """types, heights, ceiling, headroom_seen, origin, resolution."""
