"""Embree's intersection time on srt's own rays: the anchor of `cargo xtask embree` (issue 69).

Reads a folder written by xtask/src/embree.rs: per object its rest-frame vertices
(`object_K_vertices.f32`), triangles (`object_K_triangles.u32`) and every pixel's backward ray
in its rest frame (`object_K_rays.f32`: origin and direction, six f32 per pixel); the CPU
tracer's hit mask (`hits.u8`); `meta.json`. Builds one Embree scene per object and times
Embree's intersection of all of that object's rays, one thread (Embree's `rtcIntersect1M` as
`embreex` calls it), best of a few runs after the first (which also commits the scene's BVH).
Prints `seconds=` (the sum over objects), `floor_seconds=` (the same rays against one far
triangle per object: what a call costs per ray whatever the mesh), `agreement=` (the fraction of pixels where "some
object is hit" agrees with the CPU tracer) and `embree_hits=` (the fraction some ray hits).

A development tool: `pip install embreex`. srt never depends on Embree.
"""

import json
import pathlib
import sys
import time

import numpy as np
from embreex import rtcore_scene
from embreex.mesh_construction import TriangleMesh

# Timed runs per object after the first.
RUNS = 5


def best_time(scene, origins: np.ndarray, directions: np.ndarray) -> float:
    """The best of RUNS timed intersections of the rays with `scene` (after a first run)."""
    scene.run(origins, directions)
    best = float("inf")
    for _ in range(RUNS):
        start = time.perf_counter()
        scene.run(origins, directions)
        best = min(best, time.perf_counter() - start)
    return best


def object_time(folder: pathlib.Path, k: int, pixels: int) -> tuple[float, float, np.ndarray]:
    """Embree's best time over object `k`'s rays; the same rays' time against one triangle far
    beyond the object's mesh, which every ray misses at the root box (the cost of a call per ray
    whatever the mesh: the binding's and Embree's setup); and which rays hit the object."""
    vertices = np.fromfile(folder / f"object_{k}_vertices.f32", np.float32).reshape(-1, 3)
    triangles = np.fromfile(folder / f"object_{k}_triangles.u32", np.uint32).reshape(-1, 3)
    rays = np.fromfile(folder / f"object_{k}_rays.f32", np.float32).reshape(pixels, 6)
    origins = np.ascontiguousarray(rays[:, :3])
    directions = np.ascontiguousarray(rays[:, 3:])
    scene = rtcore_scene.EmbreeScene()
    TriangleMesh(scene, vertices, triangles.astype(np.int32))
    hit = scene.run(origins, directions) >= 0
    far = np.abs(vertices).max() * 1e3 + 1e3
    alone = rtcore_scene.EmbreeScene()
    corner = np.array([[far, far, far], [far + 1, far, far], [far, far + 1, far]], np.float32)
    TriangleMesh(alone, corner, np.array([[0, 1, 2]], np.int32))
    return best_time(scene, origins, directions), best_time(alone, origins, directions), hit


def main(folder: pathlib.Path) -> None:
    meta = json.loads((folder / "meta.json").read_text())
    pixels = meta["width"] * meta["height"]
    seen = np.zeros(pixels, bool)
    seconds = floor = 0.0
    for k in range(meta["objects"]):
        best, missed, hit = object_time(folder, k, pixels)
        seconds += best
        floor += missed
        seen |= hit
    cpu = np.fromfile(folder / "hits.u8", np.uint8).astype(bool)
    if cpu.size != pixels:
        sys.exit(f"hits.u8 holds {cpu.size} pixels, not {pixels}")
    print(f"seconds={seconds:.6f}")
    print(f"floor_seconds={floor:.6f}")
    print(f"agreement={float(np.mean(seen == cpu)):.6f}")
    print(f"embree_hits={float(seen.mean()):.6f}")


if __name__ == "__main__":
    main(pathlib.Path(sys.argv[1]))
