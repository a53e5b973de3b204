#!/usr/bin/env python3
"""Per-domain table from bench/run_map_g1.sh CSV: certified (all, and at fixed connectivity), growth
median/max, time median/max, MIPS3D and conformal means (VOLMAP clamp 100) over certified pairs, and
pairs whose written files the independent volmap-map-check rejected (must be 0)."""
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
doms = ['cube', 'tet', 'pyr', 'octa', 'star']
def f(x):
    try: return float(x)
    except ValueError: return None
print(f"{'domain':8} {'pairs':>5} {'certified':>9} {'fixed-conn':>10} {'growth<=5%':>10} {'growth med/max':>16} "
      f"{'time med/max (s)':>18} {'MIPS3D':>8} {'conformal':>9} {'recheck-fail':>12}")
for d in doms + ['all']:
    rs = [r for r in rows if d == 'all' or r['domain'] == d]
    if not rs: continue
    ok = [r for r in rs if r['certified'] == 'True']
    fixed = [r for r in ok if r.get('refined', 'False') != 'True']
    g = [f(r['growth']) or 0 for r in ok] or [0]
    small = [r for r in ok if (f(r['growth']) or 0) <= 0.05]
    t = [f(r['seconds']) or 0 for r in rs]
    mips = [f(r.get('mips3d', '')) for r in ok if f(r.get('mips3d', '')) is not None]
    conf = [f(r.get('conformal', '')) for r in ok if f(r.get('conformal', '')) is not None]
    bad = [r for r in ok if r.get('recheck', '0') not in ('0', '')]
    mean = lambda v: f"{statistics.mean(v):8.3f}" if v else f"{'-':>8}"
    print(f"{d:8} {len(rs):5} {len(ok):9} {len(fixed):10} {len(small):10} {statistics.median(g):7.4f}/{max(g):7.4f} "
          f"{statistics.median(t):8.2f}/{max(t):8.2f} {mean(mips)} {mean(conf):>9} {len(bad):12}")
fails = [r for r in rows if r['certified'] != 'True']
if fails:
    print('not certified:', ', '.join(f"{r['mesh']} {r['domain']} ({r['nonpositive']} bad)" for r in fails))
