#!/usr/bin/env python3
"""Which volmap-map stages lower the count, and what the others cost (issue 15's schedule).

Usage: bench/eval/stage_progress.py [--by-count] <results> [<results> ...]
  <results>: volmap-run output folders (each with cases/map/<group>/<case>/candidate.out, the
  volmap-map JSON with its `stages` list).
  --by-count: one row per stage and count the call started from (the best state before it):
  at most 5 non-positive tets, 6-20, more than 20; and, for stages that also run before the B1
  rounds (local FFM, link kernel, ...), whether the call came after the run's first `cone-repair`
  round stage (in the rounds) or before it.

A stage *progresses* when it leaves fewer exact non-positive tets than the best state before it in
the same run (the judge undoes a stage that ends higher, so the best state is what the next stage
starts from). The analysis and B0 stages (feasibility, chord-split, feasibility-and-chord-split-
reused) change no target and are skipped; a start stage (tutte3d, radial-tutte) resets the best
state, and so does a `restart`. Per stage name: calls, calls that progressed, seconds of the calls
that progressed and of those that did not, and calls after which the map was finished (0 left).
"""
import glob
import json
import os
import sys
from collections import defaultdict

NOT_JUDGED = {"feasibility", "chord-split", "feasibility-and-chord-split-reused"}
STARTS = {"tutte3d", "radial-tutte", "initial"}


def stage_lists(results):
    for path in glob.glob(os.path.join(results, "cases", "map", "*", "*", "candidate.out")):
        try:
            with open(path) as f:
                yield json.load(f)["stages"]
        except (OSError, ValueError, KeyError):
            continue


def count_bucket(best):
    return "<= 5" if best <= 5 else "6-20" if best <= 20 else "> 20"


def main():
    args = sys.argv[1:]
    by_count = "--by-count" in args
    args = [a for a in args if a != "--by-count"]
    if not args:
        sys.exit(__doc__)
    stats = defaultdict(lambda: {"calls": 0, "progressed": 0, "s_progress": 0.0, "s_none": 0.0, "finished": 0})
    runs = 0
    for results in args:
        for stages in stage_lists(results):
            runs += 1
            best = None
            in_rounds = False
            for s in stages:
                name, left = s["name"], s["nonpositive_after"]
                if name == "restart":
                    best = None
                    in_rounds = False
                    continue
                if name in NOT_JUDGED:
                    continue
                if name == "cone-repair":
                    in_rounds = True
                elif name in STARTS:  # a new start (also after a remesh): before the rounds again
                    in_rounds = False
                if best is not None and name not in STARTS:
                    key = (name, "rounds" if in_rounds else "before", count_bucket(best)) if by_count else name
                    e = stats[key]
                    e["calls"] += 1
                    if left < best:
                        e["progressed"] += 1
                        e["s_progress"] += s["seconds"]
                        e["finished"] += left == 0
                    else:
                        e["s_none"] += s["seconds"]
                best = left if best is None or name in STARTS else min(best, left)
    print(f"{runs} runs")
    if by_count:
        print("| stage | B1 rounds | started from | calls | progressed | finished the map | s (progressed) | s (no progress) |")
        print("|---|---|---|---|---|---|---|---|")
        for (name, when, bucket), e in sorted(stats.items()):
            print(f"| {name} | {when} | {bucket} | {e['calls']} | {e['progressed']} | {e['finished']} | "
                  f"{e['s_progress']:.1f} | {e['s_none']:.1f} |")
        return
    print("| stage | calls | progressed | finished the map | s (progressed) | s (no progress) |")
    print("|---|---|---|---|---|---|")
    for name, e in sorted(stats.items(), key=lambda kv: -(kv[1]["s_progress"] + kv[1]["s_none"])):
        print(f"| {name} | {e['calls']} | {e['progressed']} | {e['finished']} | {e['s_progress']:.1f} | {e['s_none']:.1f} |")


if __name__ == "__main__":
    main()
