# Types of the compiled limit meter stencils (planner/motion/_meter.c).
import numpy as np

def measure(q: np.ndarray, s: np.ndarray, move: np.ndarray, line: np.ndarray, v_limit: np.ndarray,
            linear: np.ndarray, axis_limits: np.ndarray, path_limits: np.ndarray, params: np.ndarray,
            out: np.ndarray) -> bool: ...
