#!/usr/bin/env python3
"""Fits src/software.rs's software-adapter costs to fitted.tsv (collect.py's table), by
least squares of the relative error per adapter: the GPU's whole process, less what the CPU's run spends outside its
tracer (loading, writing), against start + triangles + objects per frame + megapixels drawn.
Prints the constants and, per line, what the rule with them picks against what was faster.

    python3 fit.py fitted.tsv     (needs numpy; checked.tsv, collected afterwards, for the picks)
"""
import csv, math, sys
import numpy as np

rows = list(csv.DictReader(open(sys.argv[1]), delimiter="\t"))
for api, column in [("LAVAPIPE", "vulkan"), ("LLVMPIPE_GL", "gl")]:
    features, seconds, lines = [], [], []
    for row in rows:
        frames, samples = int(row["frames"]), int(row["samples"])
        scale = math.ceil(math.sqrt(samples)) ** 2
        megapixels = int(row["width"]) * int(row["height"]) * scale * frames / 1e6
        build, picture = float(row["build_s"]), float(row["picture_s"])
        outside = max(float(row["cpu"]) - frames * (build + picture), 0.02)
        features.append([1.0, int(row["triangles"]), frames * int(row["objects"]), megapixels])
        seconds.append(float(row[column]) - outside)
        lines.append((row["case"], float(row["cpu"]), float(row[column]), (frames - 1) * build + frames * picture))
    # Relative errors: each line weighs by its own time, so that a 6-second line does not
    # outweigh the 0.2-second ones the choice is mostly about.
    weights = 1.0 / np.array(seconds)
    costs = np.linalg.lstsq(np.array(features) * weights[:, None], np.array(seconds) * weights,
                            rcond=None)[0]
    print(f"{api}: start_seconds {costs[0]:.3f}, triangle_seconds {costs[1]:.3g}, "
          f"object_seconds {costs[2]:.4f}, megapixel_seconds {costs[3]:.4f}")
    for x, (case, cpu, gpu, cpu_left) in zip(features, lines):
        gpu_estimate = float(np.dot(x, costs))
        pick = "cpu" if cpu_left <= gpu_estimate else "gpu"
        faster = "cpu" if cpu <= gpu else "gpu"
        verdict = "" if pick == faster or abs(cpu - gpu) < 0.05 * min(cpu, gpu) else "  <- wrong"
        print(f"  {case:28} CPU left {cpu_left:6.3f} s, GPU {gpu_estimate:6.3f} s: {pick}"
              f" (measured CPU {cpu:.3f}, GPU {gpu:.3f}){verdict}")
