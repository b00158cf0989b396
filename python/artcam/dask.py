# SPDX-License-Identifier: Apache-2.0
"""Shots on a Dask cluster: a frame sequence through one camera on any ``distributed.Client``.

    from distributed import Client, LocalCluster
    import artcam, artcam.dask

    client = Client(LocalCluster(n_workers=2, threads_per_worker=1))
    result = artcam.dask.warp_sequence(client, "lens.artcam", "plates/f_%04d.exr", "out/",
                                       frames="1001-1100")
    print(result.table())

One task per frame (or per ``chunk_size`` frames), with Dask's retries; the camera is
scattered once to every worker (``broadcast=True``), so a task ships only its file names and
returns one row per frame. Each worker reads and writes the files itself (a shared file system,
as on a render farm), through the very stages of ``artcam batch``: the outputs are byte for
byte batch's, each written atomically, so a retried task is harmless. Progress is Dask's own
(the dashboard, ``client.dashboard_link``, or ``distributed.progress``).
"""
from __future__ import annotations

import dataclasses
import os
import time
import uuid
from typing import Iterable, Sequence

from . import _artcam
from ._artcam import Camera


@dataclasses.dataclass
class SequenceResult:
    """The result table: one row per frame, as ``artcam batch --json`` lists its files
    (input, output, frame, status 'written', 'skipped' or 'failed', error, width, height,
    render_ms, description, warning, worker)."""

    rows: list
    seconds: float

    def _where(self, status):
        return [r.get("frame", r["input"]) for r in self.rows if r["status"] == status]

    @property
    def done(self):
        """Frames (numbers, or inputs outside a pattern) written."""
        return self._where("written")

    @property
    def skipped(self):
        """Frames whose output existed (skip_existing)."""
        return self._where("skipped")

    @property
    def failed(self):
        """Frames that failed (their rows carry the error)."""
        return self._where("failed")

    def table(self) -> str:
        """The rows as a text table, one line per frame, then the totals."""
        lines = [f"{'frame':>8}  {'status':<8} {'ms':>8}  {'worker':<22} output / error"]
        for r in self.rows:
            frame = r.get("frame")
            what = r.get("error") if r["status"] == "failed" else r["output"]
            ms = f"{r['render_ms']:.0f}" if "render_ms" in r else ""
            lines.append(f"{'' if frame is None else frame:>8}  {r['status']:<8} {ms:>8}  "
                         f"{r.get('worker', ''):<22} {what}")
        lines.append(f"{len(self.done)} written, {len(self.skipped)} skipped, "
                     f"{len(self.failed)} failed in {self.seconds:.1f} s")
        return "\n".join(lines)

    def __str__(self):
        return self.table()


def _worker_threads() -> int:
    try:
        from distributed import get_worker
        return max(1, int(get_worker().state.nthreads))
    except (ImportError, ValueError, AttributeError):
        try:
            from distributed import get_worker
            return max(1, int(get_worker().nthreads))
        except (ImportError, ValueError, AttributeError):
            return 0


def _warp_task(items: Sequence, camera: Camera, options: dict) -> list:
    """One Dask task: `items` (frame, input, output) through the worker's copy of the camera."""
    options = dict(options)
    # The render uses as many threads as the worker was given (1 on a LocalCluster of
    # single-thread workers), not every core of the machine under every worker at once.
    if options.get("threads") is None:
        options["threads"] = _worker_threads()
    rows = _artcam.warp_files(camera, [(i, o) for _, i, o in items], options)
    try:
        from distributed import get_worker
        worker = get_worker().address
    except (ImportError, ValueError):
        worker = ""
    for (frame, _, _), row in zip(items, rows):
        if frame is not None:
            row["frame"] = frame
        row["worker"] = worker
    return rows


def plan(inputs, folder, *, suffix="", format="", first=None, frames=None, chunk=None):
    """The (frame, input, output) triples ``artcam batch`` would work through for the same
    arguments (frame None for an input that is not part of a pattern)."""
    if isinstance(inputs, (str, os.PathLike)):
        inputs = [inputs]
    inputs = [os.fspath(i) for i in inputs]
    return [tuple(t) for t in _artcam.plan_frames(inputs, os.fspath(folder), suffix=suffix,
                                                   format=format, first=first, frames=frames,
                                                   chunk=chunk)]


def warp_sequence(client, camera, inputs, folder, *, suffix: str = "", format: str = "",
                  first: int | None = None, frames: str | None = None, chunk: str | None = None,
                  chunk_size: int = 1, overwrite: bool = False, skip_existing: bool = False,
                  retries: int = 1, **options) -> SequenceResult:
    """Warps a sequence through `camera` on the cluster behind `client`, as
    ``artcam batch CAMERA INPUTS -o FOLDER`` does on one machine.

    camera: an artcam.Camera or a .artcam path.
    inputs: a printf-style pattern ("plates/f_%04d.exr"), a file, or a list of them.
    frames, chunk, first, suffix, format: batch's --frames ("1001-1100x2"), --chunk ("2/4"),
        --first, --suffix and --format.
    chunk_size: frames per Dask task (1: one task per frame).
    overwrite / skip_existing: batch's --overwrite and --skip-existing; without either an
        existing output is refused (OSError) before anything runs.
    retries: Dask's retries of a task whose worker died.
    options: batch's keywords: size=(w, h), filter, edge, threads (default: the worker's
        threads), quality, subsampling, bit_depth, colourspace, colourspace_in, colourspace_out.

    Returns a SequenceResult (rows, done, skipped, failed, table()). A frame that fails is a
    row with its error, as batch reports it; the rest go on.
    """
    start = time.monotonic()
    if not isinstance(camera, Camera):
        camera = _artcam.read(os.fspath(camera))
    items = plan(inputs, folder, suffix=suffix, format=format, first=first, frames=frames,
                 chunk=chunk)
    os.makedirs(folder, exist_ok=True)
    skipped, todo = [], []
    for frame, i, o in items:
        if skip_existing and os.path.exists(o):
            row = {"input": i, "output": o, "status": "skipped"}
            if frame is not None:
                row["frame"] = frame
            skipped.append(row)
        else:
            todo.append((frame, i, o))
    _artcam.check_outputs([o for _, _, o in todo], [i for _, i, _ in items] + [camera.name],
                          overwrite=overwrite)
    # Checked here, where the caller sees it, not once per task on the workers.
    _artcam.warp_files_options_check(options)
    rows = list(skipped)
    if todo:
        shared = client.scatter(camera, broadcast=True, hash=False)
        size = max(1, int(chunk_size))
        chunks = [todo[k:k + size] for k in range(0, len(todo), size)]
        run = uuid.uuid4().hex[:8]
        keys = [f"artcam-warp-{run}-{c[0][0] if c[0][0] is not None else k}"
                for k, c in enumerate(chunks)]
        futures = client.map(_warp_task, chunks, camera=shared, options=options, key=keys,
                             retries=retries, pure=False)
        for chunk_items, future in zip(chunks, futures):
            try:
                rows.extend(future.result())
            except Exception as error:  # a task lost beyond its retries: its frames failed
                for frame, i, o in chunk_items:
                    row = {"input": i, "output": o, "status": "failed",
                           "error": f"{i}: the task failed on the cluster: {error}"}
                    if frame is not None:
                        row["frame"] = frame
                    rows.append(row)
    order = {o: k for k, (_, _, o) in enumerate(items)}
    rows.sort(key=lambda r: order[r["output"]])
    return SequenceResult(rows, time.monotonic() - start)
