#!/usr/bin/env python3
"""Per-domain table from bench/run_map_g1.sh CSV: certified count, growth median/max, time median/max."""
import csv, statistics, sys
rows = list(csv.DictReader(open(sys.argv[1])))
doms = ['cube', 'tet', 'pyr', 'octa', 'star']
print(f"{'domain':8} {'pairs':>5} {'certified':>9} {'growth med/max':>16} {'time med/max (s)':>18}")
for d in doms + ['all']:
    rs = [r for r in rows if d == 'all' or r['domain'] == d]
    if not rs: continue
    ok = [r for r in rs if r['certified'] == 'True']
    g = [float(r['growth'] or 0) for r in ok] or [0]
    t = [float(r['seconds'] or 0) for r in rs]
    print(f"{d:8} {len(rs):5} {len(ok):9} {statistics.median(g):7.4f}/{max(g):7.4f} {statistics.median(t):8.2f}/{max(t):8.2f}")
