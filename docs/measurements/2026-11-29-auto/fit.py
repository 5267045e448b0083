#!/usr/bin/env python3
"""Fits `auto`'s method costs (crates/srt-gpu/src/auto.rs) to recorded bench lines.

Each results file here is a `cargo xtask bench` run with every line's object loads filled in
(`cargo xtask bench --object-loads IN OUT`): per object its triangles T, layers L, box layers k
and seen pixels A. In units of one triangle's LRT work a frame costs

    LRT = sum(T + b * L * A)        RT = sum(c * k * A + d)

and the rule expects the cheaper faster. For each adapter kind this samples (b, c, d)
log-uniformly (seeded), keeps the samples that miss the fewest lines (the expected-faster
method more than 5 % slower than the faster one recorded; then the smallest summed log of
picked / faster), and prints their geometric mean (the centre of what fits), each constant's
range over them, the lines the centre misses, and a leave-one-out count: each line predicted
by constants fitted without it.

Usage: python3 fit.py   (standard library only; about a minute)
"""

import json
import math
import os
import random

HERE = os.path.dirname(os.path.abspath(__file__))
KINDS = {
    "hardware (NVIDIA H200)": [
        "h200-2026-11-27-run1.json",
        "h200-2026-11-27-run2.json",
        "h200-2026-11-27-run3.json",
    ],
    "CPU adapter (lavapipe)": ["lavapipe-2026-11-29.json"],
}
TIE = 1.05


def lines(name):
    with open(os.path.join(HERE, name)) as f:
        results = json.load(f)
    frames = list(results["cases"])
    for sweep in results["sweeps"]:
        frames += sweep["frames"]
    return frames


def costs(p, line):
    b, c, d = p
    lrt = rt = 0.0
    for o in line.get("objects", []):
        lrt += o["triangles"] + b * o["layers"] * o["seen_pixels"]
        rt += c * o["box_layers"] * o["seen_pixels"] + d
    return lrt, rt


def picked_over_faster(p, line):
    lrt, rt = costs(p, line)
    picked = line["rt_ms"] if rt < lrt else line["lrt_ms"]
    return picked / min(line["rt_ms"], line["lrt_ms"])


def score(p, data):
    ratios = [picked_over_faster(p, line) for line in data]
    return (sum(r > TIE for r in ratios), round(sum(math.log(r) for r in ratios), 9))


def fit(data, samples, seed=1):
    rng = random.Random(seed)
    best, kept = None, []
    for _ in range(samples):
        p = (10 ** rng.uniform(-3, 2), 10 ** rng.uniform(-3, 2), 10 ** rng.uniform(0, 7))
        s = score(p, data)
        if best is None or s < best:
            best, kept = s, [p]
        elif s == best:
            kept.append(p)
    centre = tuple(math.exp(sum(math.log(q[k]) for q in kept) / len(kept)) for k in range(3))
    ranges = [(min(q[k] for q in kept), max(q[k] for q in kept)) for k in range(3)]
    return centre, ranges, len(kept)


def main():
    for kind, files in KINDS.items():
        data = [line for name in files for line in lines(name) if "objects" in line]
        centre, ranges, kept = fit(data, 30000)
        print(f"{kind}: {len(data)} lines with loads")
        for label, value, (low, high) in zip(
            ["per_layer_pixel b", "per_traced_pixel c", "per_traced_object d"], centre, ranges
        ):
            print(f"  {label} = {value:.3g}   (fitting samples span {low:.3g} to {high:.3g})")
        misses, logs = score(centre, data)
        print(f"  centre misses {misses} lines by more than 5 % ({kept} samples fit as well)")
        for line in data:
            r = picked_over_faster(centre, line)
            if r > TIE:
                print(f"    {line['name']} {line['width']}x{line['height']}: {r:.3f} of the faster")
        out = sum(
            score(fit(data[:i] + data[i + 1 :], 3000)[0], [data[i]])[0] for i in range(len(data))
        )
        print(f"  leave-one-out: {out} of {len(data)} lines missed")


if __name__ == "__main__":
    main()
