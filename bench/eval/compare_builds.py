#!/usr/bin/env python3
"""Two builds of volmap-map, case by case, on the small cases of a set of bench/eval/make_sets.sh.

Usage: bench/eval/compare_builds.py <old bin> <new bin> <set dir> [max tets (default 2000)]

For every boundary map G<k>_<dom>/<name>_<dom>.txt of the set whose mesh (the domain's own refined
mesh beside the map when there is one, else G<k>/<name>.mesh) has at most `max tets` tets, runs
`volmap-map MESH MAP OUT --refined-input R --threads 1 --time-limit 60 --json` with the old build,
then the new one (one case at a time, so both see the same machine), and prints per case: the tets
before any surface-map split (G<k>_unrefined/<name>.mesh when present), certified, output tets and
seconds of each build, "CHANGED" when certified or the tet count differ, ">25%" when the new count
is over 1.25 times the unsplit one. Last line: cases and certified counts of both builds.
For changes that only act on small inputs (docs/mapping.md §8 step 14a: at most 2,000 tets), this
covers every case the change can touch at a fraction of a whole set run.
"""
import glob
import json
import os
import subprocess
import sys
import tempfile


def count_tets(mesh_path):
    with open(mesh_path) as f:
        for line in f:
            if line.strip() == "Tetrahedra":
                return int(next(f).split()[0])
    return 0


def run_map(bin_dir, mesh, boundary_map, scratch):
    out = subprocess.run([os.path.join(bin_dir, "volmap-map"), mesh, boundary_map, os.path.join(scratch, "out.mesh"),
                          "--refined-input", os.path.join(scratch, "refined.mesh"), "--threads", "1",
                          "--time-limit", "60", "--json"], capture_output=True, text=True)
    result = json.loads(out.stdout)
    return result["certified"], result["output_tets"], result["seconds"]


def cases(set_dir, max_tets):
    for boundary_map in sorted(glob.glob(os.path.join(set_dir, "G*_*", "*.txt"))):
        folder = os.path.basename(os.path.dirname(boundary_map))
        group, domain = folder.split("_", 1)
        if domain in ("unrefined", "failed"):
            continue
        name = os.path.basename(boundary_map)[: -len(domain) - 5]
        mesh = boundary_map[:-4] + ".mesh"
        if not os.path.exists(mesh):
            mesh = os.path.join(set_dir, group, name + ".mesh")
        unsplit = os.path.join(set_dir, group + "_unrefined", name + ".mesh")
        if not os.path.exists(unsplit):
            unsplit = os.path.join(set_dir, group, name + ".mesh")
        if count_tets(mesh) <= max_tets:
            yield f"{group}/{name}_{domain}", mesh, boundary_map, count_tets(unsplit)


def main():
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    old_bin, new_bin, set_dir = sys.argv[1:4]
    max_tets = int(sys.argv[4]) if len(sys.argv) == 5 else 2000
    n = certified_old = certified_new = 0
    with tempfile.TemporaryDirectory() as scratch:
        for case, mesh, boundary_map, unsplit_tets in cases(set_dir, max_tets):
            old = run_map(old_bin, mesh, boundary_map, scratch)
            new = run_map(new_bin, mesh, boundary_map, scratch)
            n += 1
            certified_old += old[0]
            certified_new += new[0]
            flags = (" CHANGED" if old[:2] != new[:2] else "") + (" >25%" if new[1] > 1.25 * unsplit_tets else "")
            print(f"{case:40s} unsplit {unsplit_tets:5d}  old {old[0]!s:5} {old[1]:6d} {old[2]:6.2f} s"
                  f"  new {new[0]!s:5} {new[1]:6d} {new[2]:6.2f} s{flags}", flush=True)
    print(f"cases {n}, certified: old {certified_old}, new {certified_new}")


if __name__ == "__main__":
    main()
