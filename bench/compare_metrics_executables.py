#!/usr/bin/env python3
"""The whole `volmap-metrics` executable against the anchor process (VOLMAP's `metrics` algorithm,
bench/anchor_volmap_metrics.hpp, run as `bench_volume_maps --volmap-metrics-anchor`), alternately,
N times each, on one pair. Per process: CPU time (user + sys, from wait4's rusage, microseconds),
wall time and peak RSS (ru_maxrss). Prints the minimum and the median CPU and wall time of each side,
the largest peak RSS, the ratios ours / anchor and the machine load. Both must print the same VOLMAP
block.

Usage: bench/compare_metrics_executables.py <build dir> <in.mesh> <out.mesh> [N=10]
"""
import os
import statistics
import subprocess
import sys
import time


def run(cmd):
    start = time.monotonic()
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
    out = proc.stdout.read()
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    if status != 0:
        sys.exit(f"{cmd[0]} failed with status {status}")
    return out.decode(), usage.ru_utime + usage.ru_stime, wall, usage.ru_maxrss / 1024.0


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    build, mesh_in, mesh_out = sys.argv[1:4]
    n = int(sys.argv[4]) if len(sys.argv) > 4 else 10
    sides = {
        "ours": [os.path.join(build, "bin", "volmap-metrics"), mesh_in, mesh_out],
        "anchor": [os.path.join(build, "bin", "bench_volume_maps"), "--volmap-metrics-anchor", mesh_in, mesh_out],
    }
    best = {k: [float("inf"), float("inf"), 0.0] for k in sides}
    samples = {k: ([], []) for k in sides}  # CPU, wall
    blocks = {}
    load_before = os.getloadavg()
    for _ in range(n):
        for side in ("anchor", "ours"):
            out, cpu, wall, rss = run(sides[side])
            blocks[side] = "".join(out.splitlines(keepends=True)[:8])
            b = best[side]
            b[0], b[1], b[2] = min(b[0], cpu), min(b[1], wall), max(b[2], rss)
            samples[side][0].append(cpu)
            samples[side][1].append(wall)
    if blocks["ours"] != blocks["anchor"]:
        sys.exit("printed blocks differ:\n" + blocks["ours"] + "anchor:\n" + blocks["anchor"])
    o, a = best["ours"], best["anchor"]
    print(f"load {load_before[0]:.1f} -> {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores, {n} runs each")
    print(f"min CPU s:  ours {o[0]:.4f}  anchor {a[0]:.4f}  ratio {o[0] / a[0]:.3f} ({a[0] / o[0]:.1f}x)")
    print(f"min wall s: ours {o[1]:.4f}  anchor {a[1]:.4f}  ratio {o[1] / a[1]:.3f}")
    med = {k: [statistics.median(v) for v in samples[k]] for k in sides}
    mo, ma = med["ours"], med["anchor"]
    print(f"median CPU s:  ours {mo[0]:.4f}  anchor {ma[0]:.4f}  ratio {mo[0] / ma[0]:.3f} ({ma[0] / mo[0]:.1f}x)")
    print(f"median wall s: ours {mo[1]:.4f}  anchor {ma[1]:.4f}  ratio {mo[1] / ma[1]:.3f} ({ma[1] / mo[1]:.1f}x)")
    print(f"peak RSS MiB (max): ours {o[2]:.1f}  anchor {a[2]:.1f}")


if __name__ == "__main__":
    main()
