#!/usr/bin/env python3
"""Whole-process times of `srt render` on the CPU, on lavapipe (Vulkan) and on llvmpipe (GL),
and with `--backend auto`, in turn, median of N runs; and the CPU's cost that auto measures
(its tracer's build and a picture's estimate, which auto's note reports). The table auto's rule
(src/software.rs) was fitted to (fit.py) and is checked against.

    python3 collect.py [RUNS] [CASE-SUBSTRING...] > fitted.tsv

QUIET, where set, is a command run before each run (2026-12-07's collection,
../2026-12-07-intel/checked.tsv, ran one that put every other process at nice 19).
"""
import os, re, statistics, subprocess, sys, time

SRT = os.environ.get("SRT", "target/release/srt")
QUIET = os.environ.get("QUIET")
ENGINE = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"
# name, arguments, width, height, samples, frames, triangles, objects
CASES = [
    ("teaser 1280x720", ["teaser"], 1280, 720, 1, 1, 3768, 3),
    ("teaser 1920x1080", ["teaser", "--width", "1920", "--height", "1080"], 1920, 1080, 1, 1, 3768, 3),
    ("teaser 3840x2160", ["teaser", "--width", "3840", "--height", "2160"], 3840, 2160, 1, 1, 3768, 3),
    ("teaser 640x360", ["teaser", "--width", "640", "--height", "360"], 640, 360, 1, 1, 3768, 3),
    ("teaser 320x180 256 samples", ["teaser", "--width", "320", "--height", "180", "--samples", "256"], 320, 180, 256, 1, 3768, 3),
    ("teaser 1280x720 16 samples", ["teaser", "--samples", "16"], 1280, 720, 16, 1, 3768, 3),
    ("teaser 10 frames", ["teaser", "--frames", "10"], 1280, 720, 1, 10, 3768, 3),
    ("teaser 30 frames", ["teaser", "--frames", "30"], 1280, 720, 1, 30, 3768, 3),
    ("2CylinderEngine 1280x720", [ENGINE], 1280, 720, 1, 1, 121496, 1),
    ("2CylinderEngine 1920x1080", [ENGINE, "--width", "1920", "--height", "1080"], 1920, 1080, 1, 1, 121496, 1),
    ("flythrough 1280x720", ["flythrough"], 1280, 720, 1, 1, 1668, 45),
    ("flythrough 1920x1080", ["flythrough", "--width", "1920", "--height", "1080"], 1920, 1080, 1, 1, 1668, 45),
    ("flythrough 5 frames", ["flythrough", "--frames", "5"], 1280, 720, 1, 5, 1668, 45),
    ("fig10-cube50 1280x720", ["fig10-cube50"], 1280, 720, 1, 1, 300, 1),
    ("spider 1280x720", ["spider"], 1280, 720, 1, 1, 1368, 1),
    ("cube-1.9M 1280x720", ["fig10-cube200", "--set", "object.cube.shape.subdivisions=400"], 1280, 720, 1, 1, 1920000, 1),
]
MODES = {
    "cpu": ({}, ["--backend", "cpu"]),
    "vulkan": ({"WGPU_BACKEND": "vulkan"}, ["--backend", "gpu"]),
    "gl": ({"WGPU_BACKEND": "gl"}, ["--backend", "gpu"]),
    "auto_vulkan": ({"WGPU_BACKEND": "vulkan"}, ["--backend", "auto"]),
    "auto_gl": ({"WGPU_BACKEND": "gl"}, ["--backend", "auto"]),
}


def run(args, env, out):
    if QUIET:
        subprocess.run(QUIET, shell=True)
    start = time.perf_counter()
    done = subprocess.run([SRT, "render", *args, "-o", out], env=dict(os.environ, **env),
                          capture_output=True, text=True)
    took = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"failed: {args} {env}: {done.stderr}")
    return took, done.stderr + done.stdout


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    only = sys.argv[2:]
    out = os.path.join(os.environ.get("TMPDIR", "/tmp"), "srt-collect.png")
    print("case\twidth\theight\tsamples\tframes\ttriangles\tobjects\tbuild_s\tpicture_s\t"
          "cpu\tvulkan\tgl\tauto_vulkan\tauto_gl\tauto_vulkan_chose\tauto_gl_chose", flush=True)
    for name, args, width, height, samples, frames, triangles, objects in CASES:
        if only and not any(o in name for o in only):
            continue
        times = {mode: [] for mode in MODES}
        builds, pictures, chose = [], [], {}
        for _ in range(runs):
            for mode, (env, extra) in MODES.items():
                took, said = run(args + extra, env, out)
                times[mode].append(took)
                for build, picture in re.findall(r"tracer built in ([\d.]+) s, a picture traced in about ([\d.]+) s", said):
                    builds.append(float(build))
                    pictures.append(float(picture))
                if mode.startswith("auto"):
                    chose[mode] = "cpu" if "auto renders on the CPU" in said else "gpu"
        median = {mode: statistics.median(values) for mode, values in times.items()}
        print(f"{name}\t{width}\t{height}\t{samples}\t{frames}\t{triangles}\t{objects}\t"
              f"{statistics.median(builds):.4f}\t{statistics.median(pictures):.4f}\t"
              + "\t".join(f"{median[m]:.3f}" for m in MODES)
              + f"\t{chose['auto_vulkan']}\t{chose['auto_gl']}", flush=True)


main()
