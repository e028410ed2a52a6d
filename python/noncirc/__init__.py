"""noncirc: non-circular gear transplanting mechanisms, from Python at the Rust core's speed.

Load a scene, evaluate one design or a whole NumPy batch in parallel, run a search:

>>> import noncirc
>>> scene = noncirc.Scene.builtin("paper")
>>> result = noncirc.evaluate(scene)
>>> round(result["centre_distance_mm"], 3)
85.018
"""

from ._noncirc import NoncircError, Scene, UnknownNameError, __version__, evaluate, evaluate_batch, measures, optimise

__all__ = ["NoncircError", "Scene", "UnknownNameError", "evaluate", "evaluate_batch", "measures", "optimise", "__version__"]
