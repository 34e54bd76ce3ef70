"""What a finished run leaves: its summary's tracking report and the saved trace of every
set-point sent with the drives' actual positions (``last_run.npz`` in the state folder)."""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from app.machine.model import TrackingReport
from app.machine.motion.jobs import Job
from ethercat.worker import WorkerSnapshot
from planner.core.files import write_output

__all__ = ["save_trace", "tracking_report"]


def tracking_report(snap: WorkerSnapshot, axes: tuple[str, ...], trace_path: str) -> TrackingReport:
    """Reference against actual per axis over the run so far (paper Eq. 18, Table 4)."""
    t = snap.tracking
    return TrackingReport(
        axes=axes,
        samples=int(t.samples),
        rmse=tuple(t.rmse),
        mse=tuple(t.mse),
        max_abs=tuple(t.max_abs),
        trace_path=trace_path,
    )


def save_trace(job: Job, path: str, home_offset: np.ndarray, axes: tuple[str, ...], ts_s: float,
               failed: Callable[[str], object]) -> str:
    """The job's trace in machine coordinates to ``path`` (NPZ: t, reference, actual, axes,
    rmse, mse); the path, or "" when the job recorded nothing or it could not be written
    (``failed`` is then told why)."""
    try:
        return _write_trace(job, path, home_offset, axes, ts_s)
    except OSError as exc:
        failed(f"cannot save the run trace: {exc}")
        return ""


def _write_trace(job: Job, path: str, home_offset: np.ndarray, axes: tuple[str, ...], ts_s: float) -> str:
    if not job.trace:
        return ""
    cyc = np.concatenate([c for c, _, _ in job.trace])
    ref = np.concatenate([r for _, r, _ in job.trace]) - home_offset
    act = np.concatenate([a for _, _, a in job.trace]) - home_offset
    e = ref - act
    mse = (e * e).mean(axis=0) if len(e) else np.zeros(len(axes))
    write_output(path, lambda fh: np.savez_compressed(
        fh, t=cyc * ts_s, reference=ref, actual=act, axes=np.array(axes), rmse=np.sqrt(mse), mse=mse))
    return path
