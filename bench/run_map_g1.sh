#!/usr/bin/env bash
# Table of volmap-map over the 100 G1 pairs (20 meshes × cube tet pyr octa star), one line per pair.
# Usage: bench/run_map_g1.sh <build/bin> <data/volmap> <out.csv> [extra volmap-map args...]
#   e.g. bench/run_map_g1.sh build/bin ../shared/data/volmap /tmp/g1_ffm.csv --threads 1 --time-limit 60 --no-refine
#        bench/run_map_g1.sh build/bin ../shared/data/volmap /tmp/g1_tlc.csv --threads 1 --time-limit 60 --method tlc
# Summarise with bench/summarise_map_g1.py <out.csv>.
#
# Measured 2026-11-23 on the shared, heavily loaded 2-core machine (load ~12), --threads 1
# --time-limit 20 --no-refine --no-quality (wall-clock budget; B1 refinement not implemented):
#   domain pairs certified  time med/max (s)
#   cube     20     12        2.81 / 20.08
#   tet      20     12        4.22 / 20.10
#   pyr      20     14        3.30 / 20.06
#   octa     20     12        4.94 / 20.07
#   star     20      6       20.02 / 20.10
#   all     100     56        6.37 / 20.10   (growth 0 everywhere; 53 certified by the TLC stage)
# Re-running the 22 failures with <= 13 bad tets at --time-limit 60 certified 9 more (65/100).
# Cascade TLC share (volmap-map --tlc-share), MESHES="bone duck" subset, same flags, --time-limit 20:
#   --tlc-share 0.5 (default): 8/10 certified; --tlc-share 0.8: 8/10 (same two failures, same counts).
# s2-untangle cascade (local FFM with Newton on the bad region, global FFM with stall hand-over),
# measured 2026-11-23 13:33-13:48 UTC, load ~2, same flags (--threads 1 --time-limit 20 --no-refine
# --no-quality), before = main 23242ab, after = s2-untangle, run back to back:
#   MESHES="bone duck bird" (15 pairs): before 8/15, median 18.12 s; after 8/15, median 1.17 s
#     (bone octa 18.1 s by ffm-regular -> 1.2 s by ffm-local; bird still 15-61 bad in both).
#   17 pairs that failed in the table above (homer cube, moai/sphinx/buste/bimba/bunny star, ramses x4,
#   bunny octa, blade cube/tet, hand cube, camile_hand cube/octa, mouse cube): before 7/17, after 7/17
#     (after gains sphinx star, 10.5 s by ffm-local; hand cube certified by the before binary once at
#     10.7 s and failed on its re-run: TLC stopped at its time share is not reproducible under load).
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
