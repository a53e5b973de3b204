#!/usr/bin/env bash
# Table of volmap-map over the 100 G1 pairs (20 meshes × cube tet pyr octa star), one line per pair.
# Usage: bench/run_map_g1.sh <build/bin> <data/volmap> <out.csv> [extra volmap-map args...]
#   e.g. bench/run_map_g1.sh build/bin ../shared/data/volmap /tmp/g1_ffm.csv --threads 1 --time-limit 60 --no-refine
#        bench/run_map_g1.sh build/bin ../shared/data/volmap /tmp/g1_tlc.csv --threads 1 --time-limit 60 --method tlc
# Summarise with bench/summarise_map_g1.py <out.csv>.
#
# The issue-6 table is now produced by volmap-run (exact re-check, metrics, resume, one Markdown
# table per label, TLC beside ours). The full 100 G1 pairs (20 meshes x 5 domains); each label takes at
# most ~100 x 35 s / 2 jobs = 30 min (bone+duck, 10 pairs, -j1, --time-limit 20: 15-46 s per label):
#   B=build/bin; D=/work/shared/data/volmap; O=results/g1-table
#   $B/volmap-run $D --groups G1 --method map --method-args="--threads 1 --time-limit 30" --timeout 120 -j2 --out $O
#   $B/volmap-run $D --groups G1 --method map --label map-fixed --method-args="--threads 1 --time-limit 30 --no-refine" --timeout 120 -j2 --out $O
#   $B/volmap-run $D --groups G1 --method tlc --method-args="--threads 1 --time-limit 30" --timeout 120 -j2 --out $O
#   $B/volmap-run table $O        # prints the table and writes $O/table.md (add --resume to continue a run)
# Measured 2026-11-23 at 79dd9a0 with -j1 (one case at a time, 2-core machine, load ~1-3):
#   map        100/100 certified (62 without refinement, 38 by B1 cone repair), growth -1.98 %..0 %,
#              time median 3.34 s, max 16.0 s
#   map-fixed   68/100 (--no-refine), time median 6.8 s, max 30.3 s
#   tlc         58/100 (at 303fa9b; 47/80 on cube/tet/pyr/octa; the paper reports 63 %)
# This script stays for quick CSV runs with any volmap-map flags.
set -u
bin=$1; data=$2; out=$3; shift 3
tmp=$(mktemp -d)
echo "mesh,domain,exit,certified,nonpositive,input_tets,output_tets,growth,seconds,certified_by,refined,recheck,mips3d,conformal" > "$out"
for mesh in ${MESHES:-"$data"/G1/*.mesh}; do
  name=$(basename "$mesh" .mesh)
  for dom in cube tet pyr octa star; do
    map="$data/G1_$dom/${name}_$dom.txt"
    [ -f "$map" ] || continue
    rm -f "$tmp/out.mesh" "$tmp/in.mesh"
    json=$("$bin/volmap-map" "$mesh" "$map" "$tmp/out.mesh" --refined-input "$tmp/in.mesh" --json "$@" 2>/dev/null)
    code=$?
    # Independent re-check of the written files (exit 0 = every tet exactly positive) and the
    # VOLMAP metrics (clamped at 100, as in the paper) on certified outputs.
    recheck=""; metrics="{}"
    if [ -f "$tmp/out.mesh" ]; then
      src="$mesh"; [ -f "$tmp/in.mesh" ] && src="$tmp/in.mesh"
      "$bin/volmap-map-check" "$src" "$tmp/out.mesh" >/dev/null 2>&1; recheck=$?
      [ "$code" = 0 ] && metrics=$("$bin/volmap-metrics" "$src" "$tmp/out.mesh" --json 2>/dev/null)
    fi
    MAPJSON="$json" METRICS="$metrics" python3 -c "
import json,os
try: j=json.loads(os.environ['MAPJSON'])
except Exception: j={}
try: m=json.loads(os.environ['METRICS']).get('energies',{})
except Exception: m={}
e=lambda k: m.get(k,{}).get('mean','') if m.get(k,{}).get('defined',True) else ''
print(','.join(str(x) for x in ['$name','$dom',$code,j.get('certified',False),j.get('zero',0)+j.get('negative',0) if j else -1,
      j.get('input_tets',''),j.get('output_tets',''),j.get('growth',''),j.get('seconds',''),j.get('certified_by',''),j.get('refined',''),
      '$recheck',e('mips3d'),e('conformal')]))" >> "$out"
  done
done
rm -rf "$tmp"
