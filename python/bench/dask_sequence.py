#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""artcam.dask on a LocalCluster against `artcam batch`, on one frame sequence.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/dask_sequence.py build/app/artcam \
        [--frames 48] [--size 6000x4000] [--rounds 3] [--workdir DIR]

Makes a JPEG sequence in code (a textured 24 MP frame, shifted per frame) and a lens camera,
then alternates, round by round: `artcam batch CAM seq/f_%04d.jpg -o out-batch` and
artcam.dask.warp_sequence on a LocalCluster of 2 single-thread worker processes (the cluster is
started once, before the rounds, as a farm's is; its start-up is printed apart). A last run on a
cluster of 1 worker gives the scaling. Every dask output is compared byte for byte with batch's.
"""
import argparse
import filecmp
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import artcam
import artcam.dask
from distributed import Client, LocalCluster


def make_sequence(folder, frames, width, height):
    os.makedirs(folder, exist_ok=True)
    y, x = np.mgrid[0:height, 0:width].astype(np.float32)
    base = np.stack([x / width, y / height, 0.5 + 0.5 * np.sin(x / 9.0) * np.cos(y / 7.0)], -1)
    rng = np.random.default_rng(1)
    base += rng.normal(0, 0.03, base.shape).astype(np.float32)  # grain, as a photo has
    base = np.clip(np.round(base * 255), 0, 255).astype(np.uint8)
    for k in range(frames):
        artcam.write_image(os.path.join(folder, "f_%04d.jpg" % (1001 + k)),
                           np.roll(base, 17 * k, axis=1), quality=92)


def timed(fn):
    t = time.monotonic()
    fn()
    return time.monotonic() - t


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("cli")
    ap.add_argument("--frames", type=int, default=48)
    ap.add_argument("--size", default="6000x4000")
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--workdir")
    a = ap.parse_args()
    w, h = map(int, a.size.split("x"))
    work = a.workdir or tempfile.mkdtemp(prefix="artcam-dask-bench-")
    seq = os.path.join(work, "seq")
    if not os.path.exists(os.path.join(seq, "f_%04d.jpg" % (1000 + a.frames))):
        make_sequence(seq, a.frames, w, h)
    cam = os.path.join(work, "lens.artcam")
    subprocess.run([a.cli, "preset", "lens-distortion", "--k1", "-0.1", "--k2", "0.02", "--size",
                    a.size, "-o", cam, "--overwrite"], check=True, capture_output=True)
    pattern = os.path.join(seq, "f_%04d.jpg")
    out_b, out_d = os.path.join(work, "out-batch"), os.path.join(work, "out-dask")

    def batch():
        subprocess.run([a.cli, "batch", cam, pattern, "-o", out_b, "--first", "1001",
                        "--overwrite", "--quiet"], check=True, capture_output=True)

    def on(client):
        def run():
            r = artcam.dask.warp_sequence(client, cam, pattern, out_d, first=1001, overwrite=True)
            assert not r.failed, r.table()
        return run

    t0 = time.monotonic()
    with LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        start_s = time.monotonic() - t0
        b_times, d_times = [], []
        for _ in range(a.rounds):
            b_times.append(timed(batch))
            d_times.append(timed(on(client)))
    with LocalCluster(n_workers=1, threads_per_worker=1, dashboard_address=None) as cluster, \
            Client(cluster) as client:
        one = timed(on(client))
    names = sorted(os.listdir(out_b))
    same = all(filecmp.cmp(os.path.join(out_b, n), os.path.join(out_d, n), shallow=False)
               for n in names)
    ratios = [d / b for d, b in zip(d_times, b_times)]
    print(f"{a.frames} frames {a.size} JPEG, {a.rounds} paired rounds, load "
          f"{os.getloadavg()[0]:.2f}; cluster start {start_s:.1f} s")
    print(f"artcam batch median {statistics.median(b_times):.1f} s "
          f"({' '.join('%.1f' % t for t in b_times)})")
    print(f"artcam.dask 2 workers median {statistics.median(d_times):.1f} s "
          f"({' '.join('%.1f' % t for t in d_times)}); ratio median {statistics.median(ratios):.3f} "
          f"(target <= 1.15)")
    print(f"artcam.dask 1 worker {one:.1f} s: 2 workers are {one / statistics.median(d_times):.2f}x "
          f"faster")
    print(f"outputs byte-identical to batch: {same} ({len(names)} files)")
    if not a.workdir:
        shutil.rmtree(work)
    return 0 if same and statistics.median(ratios) <= 1.15 else 1


if __name__ == "__main__":
    sys.exit(main())
