"""noncirc: non-circular gear transplanting mechanisms, from Python at the Rust core's speed.

Load a scene, evaluate one design or a whole NumPy batch in parallel, run a search:

>>> import noncirc
>>> scene = noncirc.Scene.builtin("paper")
>>> result = noncirc.evaluate(scene)
>>> round(result.centre_distance_mm, 3)
85.018
>>> result.objectives["picking_angle"].met
True

Errors are `NoncircError` (a ValueError), by kind `SceneError`, `ParameterError`,
`ModelError` and `UnknownNameError`; files that cannot be read raise OSError
(`FileNotFoundError`), values of the wrong type `TypeError`; a failure inside noncirc (a
bug, not bad input) `InternalError` (a RuntimeError).
"""

from ._noncirc import (
    InternalError,
    ModelError,
    NoncircError,
    ParameterError,
    Scene,
    SceneError,
    UnknownNameError,
    __version__,
    measures,
    robustness,
    sensitivity,
)
from .api import cad, dynamics, evaluate, evaluate_batch, fit, inverse, optimise, repair
from .progress import ProgressBar
from .results import (
    Batch,
    Body,
    CadInstance,
    CadPart,
    CadResult,
    Change,
    Condition,
    ConstraintReading,
    Design,
    Dynamics,
    Evaluation,
    EventShift,
    FitMeasure,
    FitResult,
    GearStrength,
    Goal,
    InverseResult,
    Objective,
    Place,
    PoseFit,
    Quantity,
    RepairResult,
    SearchResult,
    SpeedFluctuation,
    Strength,
)

__all__ = [
    "Batch",
    "Body",
    "CadInstance",
    "CadPart",
    "CadResult",
    "Change",
    "Condition",
    "ConstraintReading",
    "Design",
    "Dynamics",
    "Evaluation",
    "EventShift",
    "FitMeasure",
    "FitResult",
    "GearStrength",
    "Goal",
    "InternalError",
    "InverseResult",
    "ModelError",
    "NoncircError",
    "Objective",
    "ParameterError",
    "Place",
    "PoseFit",
    "ProgressBar",
    "Quantity",
    "RepairResult",
    "Scene",
    "SceneError",
    "SearchResult",
    "SpeedFluctuation",
    "Strength",
    "UnknownNameError",
    "cad",
    "dynamics",
    "evaluate",
    "evaluate_batch",
    "fit",
    "inverse",
    "measures",
    "optimise",
    "repair",
    "robustness",
    "sensitivity",
    "__version__",
]
