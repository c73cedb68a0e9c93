"""The paper's plane segmentation and maps on any range data (a real depth camera's too)."""
from ._core import perception as _perception

segment = _perception.segment
depth_to_points = _perception.depth_to_points
Maps = _perception.Maps

__all__ = ["segment", "depth_to_points", "Maps"]
