# Types of the compiled sample geometry (planner/geometry/_kernels.c).
import numpy as np

def contour_error(start: np.ndarray, delta: np.ndarray, length: np.ndarray, is_arc: np.ndarray,
                  is_blend: np.ndarray, turn: np.ndarray, first: np.ndarray, second: np.ndarray,
                  cx: np.ndarray, cy: np.ndarray, r0: np.ndarray, r1: np.ndarray, theta0: np.ndarray,
                  sweep: np.ndarray, row: np.ndarray, q: np.ndarray, u: np.ndarray,
                  out: np.ndarray) -> int: ...
def positions(start: np.ndarray, delta: np.ndarray, end: np.ndarray, length: np.ndarray,
              is_arc: np.ndarray, is_blend: np.ndarray, spiral: np.ndarray, turn: np.ndarray,
              first: np.ndarray, second: np.ndarray, cx: np.ndarray, cy: np.ndarray, r0: np.ndarray,
              r1: np.ndarray, theta0: np.ndarray, sweep: np.ndarray, far_radius: float, row: np.ndarray,
              u: np.ndarray, out: np.ndarray) -> int: ...
