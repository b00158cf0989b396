#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Camera.warp on a numpy array against the engine's own render of the same camera and size.

    PYTHONPATH=build/python /usr/bin/python3 python/bench/warp_array.py build/app/artcam [--rounds 9]

Engine: `artcam bench render --cameras CAM` (the fused render's median on an RGB8 image made in
code, rendered into one warm output buffer). Python: the median wall time of camera.warp(array, out=buffer) on
a 6000×4000 RGB8 array, the same work; and of camera.warp(array) into a new array, whose first
touch of fresh pages the engine's figure leaves out. Peak memory: the process's peak RSS growth (VmHWM) from before the input
array exists to after the warp, against input + output + 64 MiB. Rounds alternate engine and
Python so load drifts hit both."""
import argparse
import csv
import io
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import artcam

MIB = 1 << 20


def peak_rss_bytes():
    with open("/proc/self/status") as f:
        for line in f:
            if line.startswith("VmHWM:"):
                return int(line.split()[1]) * 1024
    raise RuntimeError("no VmHWM")


def make_photo(width, height):
    """A 24 MP RGB8 photo with no float temporaries (they would inflate the peak)."""
    photo = np.empty((height, width, 3), np.uint8)
    photo[..., 0] = (np.arange(width) % 251).astype(np.uint8)[None, :]
    photo[..., 1] = (np.arange(height) % 241).astype(np.uint8)[:, None]
    photo[..., 2] = 128
    return photo


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("cli")
    parser.add_argument("--rounds", type=int, default=9)
    parser.add_argument("--size", default="6000x4000")
    parser.add_argument("--threads", type=int, default=0)
    args = parser.parse_args()
    width, height = map(int, args.size.split("x"))
    tmp = tempfile.mkdtemp()
    cam_path = os.path.join(tmp, "lens.artcam")
    subprocess.run([args.cli, "preset", "lens-distortion", "--k1", "-0.1", "--k2", "0.02",
                    "--size", args.size, "-o", cam_path], check=True, capture_output=True)
    camera = artcam.read(cam_path)
    before = peak_rss_bytes()
    photo = make_photo(width, height)
    out = camera.warp(photo, threads=args.threads)
    grown = peak_rss_bytes() - before
    bound = photo.nbytes + out.nbytes + 64 * MIB
    del out
    engine, python, reused = [], [], []
    into = camera.warp(photo, threads=args.threads)
    threads = str(args.threads or os.cpu_count())
    for _ in range(args.rounds):
        done = subprocess.run([args.cli, "bench", "render", "--cameras", cam_path, "--size",
                               args.size, "--reps", "3", "--threads", threads, "--no-suite",
                               "--no-e2e"], check=True, capture_output=True, text=True)
        rows = [r for r in csv.DictReader(io.StringIO(done.stdout))
                if r.get("kernel") == "lens" and r.get("filter") == "bilinear"]
        engine.append(float(rows[0]["ms"]))
        t = time.perf_counter()
        camera.warp(photo, threads=args.threads)
        python.append((time.perf_counter() - t) * 1000)
        t = time.perf_counter()
        camera.warp(photo, threads=args.threads, out=into)
        reused.append((time.perf_counter() - t) * 1000)
    ratios = [p / e for p, e in zip(reused, engine)]
    fresh = [p / e for p, e in zip(python, engine)]
    print(f"size {args.size} RGB8, threads {threads}, {args.rounds} paired rounds, "
          f"load {os.getloadavg()[0]:.2f}")
    print(f"engine render median {statistics.median(engine):.1f} ms, "
          f"camera.warp(out=) median {statistics.median(reused):.1f} ms, "
          f"ratio median {statistics.median(ratios):.3f} (target <= 1.10); "
          f"into a new array {statistics.median(python):.1f} ms, "
          f"ratio {statistics.median(fresh):.3f}")
    print(f"peak memory growth {grown / MIB:.1f} MiB, bound input + output + 64 MiB = "
          f"{bound / MIB:.1f} MiB: {'within' if grown <= bound else 'OVER'}")
    return 0 if statistics.median(ratios) <= 1.10 and grown <= bound else 1


if __name__ == "__main__":
    sys.exit(main())
