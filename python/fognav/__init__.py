"""fognav: closed-loop humanoid navigation from Python.

Run whole missions (run), step them with your own decisions (Mission) and run the paper's
perception on your own range data (fognav.perception). docs/python.md has the API and examples.
"""
from . import _core
from ._core import (CELL_TYPES, HEADINGS, MOVES, BORDER, FLOOR, OBSTACLE, STAIRS, TUNNEL,
                    UNKNOWN, InputError, Mission, OutputError, Scenario, SimError,
                    load_scenario, param_defaults, run)
from . import perception

__all__ = ["CELL_TYPES", "HEADINGS", "MOVES", "BORDER", "FLOOR", "OBSTACLE", "STAIRS", "TUNNEL",
           "UNKNOWN", "InputError", "Mission", "OutputError", "Scenario", "SimError",
           "load_scenario", "param_defaults", "run", "perception"]
