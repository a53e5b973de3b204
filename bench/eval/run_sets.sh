#!/usr/bin/env bash
# Measures a build of volmap-map on the evaluation sets of bench/eval/make_sets.sh (issue 15).
#
# Usage: bench/eval/run_sets.sh <bin> <sets> <results> [set ...]
#   <bin>      the binaries to measure (a snapshot: the lead rebuilds main meanwhile)
#   <sets>     the output folder of make_sets.sh
#   <results>  where results go: <results>/<set>/ (volmap-run's results.jsonl, cases/, table.md)
#   sets       default: thin thin_coarse coarse g1sphere tetmeshes maps surfaces
#   env        TIME_LIMIT (volmap-map --time-limit, default 60), TIMEOUT (volmap-run --timeout, default 150),
#              JOBS (volmap-run -j, default 1: cases one at a time; 2 on two idle cores = load 2),
#              MAP_ARGS (more volmap-map options for every case, e.g. "--no-refine" for the fixed-
#              connectivity tables of issue 18; default none)
#
# Per layout set:
#   1. every sphere map is re-checked by `volmap-surface-map-check <mesh> <map>` WITHOUT options (the
#      kernel is then the centroid of the boundary image, as in VOLMAP's own check) and with
#      --domain sphere (the tool's self-check): <results>/<set>/sphere_checks.jsonl;
#   2. `volmap-run <set> --method map --method-args="--threads 1 --time-limit $TIME_LIMIT"
#      --timeout $TIMEOUT -j1 --resume`: volmap-run gives the built-in mapper --refined-input, so
#      refinement is allowed, and re-checks every output exactly (volmap-map-check --absolute);
#   3. `volmap-run table`: <results>/<set>/table.md;
#   4. (before 2) each domain's surface map alone on the unrefined mesh: surface_standalone.jsonl.
# The maps set runs `volmap-map <object> - out.mesh --initial <parameter> --refined-input r.mesh
# --threads 1 --time-limit $TIME_LIMIT --json` per line of maps.tsv (with a .txt parameter, a
# boundary map: `volmap-map <object> <parameter> out.mesh ...`) and re-checks with
# volmap-map-check --absolute: <results>/maps/results.jsonl.
# The load average is logged every 5 minutes to <results>/<set>/load.log (the machine is shared:
# time-limited runs depend on it). Then bench/eval/summarise.py <sets> <results> writes the summary.
set -euo pipefail

[ $# -ge 3 ] || { sed -n '2,25p' "$0"; exit 2; }
source "$(dirname "$0")/common.sh"
BIN=$(absolute_dir "$1")
SETS_DIR=$(absolute_dir "$2")
RESULTS=$(absolute_dir "$3")
shift 3
SETS=("${@:-${ALL_SETS[@]}}")
TIME_LIMIT=${TIME_LIMIT:-60}
TIMEOUT=${TIMEOUT:-150}
JOBS=${JOBS:-1}
MAP_ARGS=${MAP_ARGS:-}

sphere_checks() {  # <set dir> <results dir>
  local out=$2/sphere_checks.jsonl map group name mesh plain domain
  : > "$out.tmp"
  for map in "$1"/G*_sphere/*_sphere.txt; do
    [ -f "$map" ] || continue
    group=$(basename "$(dirname "$map")"); group=${group%_sphere}
    name=$(basename "$map" _sphere.txt)
    mesh=$1/${group}_sphere/${name}_sphere.mesh  # its own mesh (make_sets.sh --mesh-per-domain)
    [ -f "$mesh" ] || mesh=$1/$group/$name.mesh
    [ -f "$mesh" ] || continue
    plain=$("$BIN/volmap-surface-map-check" "$mesh" "$map" --json 2>/dev/null || true)
    domain=$("$BIN/volmap-surface-map-check" "$mesh" "$map" --domain sphere --json 2>/dev/null || true)
    python3 -c 'import json,sys; print(json.dumps({"case": sys.argv[1], "mesh": sys.argv[2], "map": sys.argv[3],
      "plain": json.loads(sys.argv[4] or "{}"), "domain": json.loads(sys.argv[5] or "{}")}))' \
      "$group/${name}_sphere" "$mesh" "$map" "$plain" "$domain" >> "$out.tmp"
  done
  mv "$out.tmp" "$out"
}

# Each domain's surface map alone on the mesh before any split (G<k>_unrefined/, or G1 when there
# is none, as in g1sphere): its split growth and its exit, without the other domains' splits the published mesh
# carries. <results>/<set>/surface_standalone.jsonl, one line per (input, domain).
surface_standalone() {  # <set dir> <results dir>
  local out=$2/surface_standalone.jsonl mesh group name dom r rc
  : > "$out.tmp"
  local meshes=("$1"/G*_unrefined/*.mesh)
  [ -f "${meshes[0]}" ] || meshes=("$1"/G1/*.mesh)  # g1sphere: G1 is unrefined
  for mesh in "${meshes[@]}"; do
    [ -f "$mesh" ] || continue
    group=$(basename "$(dirname "$mesh")"); group=${group%_unrefined}
    name=$(basename "$mesh" .mesh)
    for dom in cube tet pyr octa star sphere; do
      r=$(mktemp -d)
      rc=0
      "$BIN/volmap-surface-map" "$dom" "$mesh" "$r/map.txt" --refined "$r/refined.mesh" --json > "$r/out.json" 2> "$r/err.txt" || rc=$?
      python3 -c 'import json,sys
try: j=json.load(open(sys.argv[5]))
except Exception: j={}
err=open(sys.argv[6]).read().strip().splitlines()
print(json.dumps({"group": sys.argv[1], "name": sys.argv[2], "domain": sys.argv[3], "exit_code": int(sys.argv[4]),
  "tets": j.get("tets"), "added_vertices": j.get("added_vertices"), "seconds": j.get("seconds"),
  "error": err[0][:400] if err else ""}))' "$group" "$name" "$dom" "$rc" "$r/out.json" "$r/err.txt" >> "$out.tmp"
      rm -rf "$r"
    done
  done
  mv "$out.tmp" "$out"
}

run_maps() {  # <results dir>
  local out=$1 name object parameter note work rc check boundary initial
  mkdir -p "$out/cases"
  touch "$out/results.jsonl"
  while IFS=$'\t' read -r name object parameter note; do
    [ "$name" = name ] && continue
    grep -q "\"name\": \"$name\"" "$out/results.jsonl" && continue
    work=$out/cases/$name
    mkdir -p "$work"
    rm -f "$work/out.mesh" "$work/refined.mesh"
    rc=skipped
    check="{}"
    if [ -z "$note" ]; then
      rc=0
      boundary=- initial=(--initial "$parameter")
      if [[ $parameter == *.txt ]]; then boundary=$parameter initial=(); fi
      /usr/bin/time -f '%e %U %S' -o "$work/time.txt" timeout "$TIMEOUT" "$BIN/volmap-map" "$object" "$boundary" "$work/out.mesh" \
        "${initial[@]}" --refined-input "$work/refined.mesh" --threads 1 --time-limit "$TIME_LIMIT" $MAP_ARGS --json \
        > "$work/map.json" 2> "$work/map.err" || rc=$?
      if [ -f "$work/out.mesh" ]; then
        local src=$object
        [ -f "$work/refined.mesh" ] && src=$work/refined.mesh
        check=$("$BIN/volmap-map-check" "$src" "$work/out.mesh" --absolute --json 2>/dev/null || true)
      fi
      rm -f "$work/out.mesh" "$work/refined.mesh"
    fi
    python3 - "$name" "$object" "$parameter" "$note" "$rc" "$work" "$check" >> "$out/results.jsonl" <<'EOF'
import json, os, sys
name, obj, par, note, rc, work, check = sys.argv[1:]
def load(p):
    try: return json.load(open(p))
    except Exception: return {}
def first(p):
    try: return next((l.strip() for l in open(p) if l.strip()), "")
    except Exception: return ""
try: check = json.loads(check)
except Exception: check = {}
try:
    lines = [l for l in open(os.path.join(work, "time.txt")).read().splitlines() if l.strip()]
    wall, user, system = (float(x) for x in lines[-1].split()[-3:])  # GNU time may add a status line first
except Exception:
    wall = user = system = None
print(json.dumps({"name": name, "object": obj, "parameter": par, "note": note, "exit_code": rc,
                  "wall_s": wall, "cpu_s": user + system if user is not None else None,
                  "map": load(os.path.join(work, "map.json")), "stderr": first(os.path.join(work, "map.err")),
                  "check": check}))
EOF
    echo "  maps/$name: exit $rc"
  done < "$SETS_DIR/maps/maps.tsv"
}

for set in "${SETS[@]}"; do
  out=$RESULTS/$set
  mkdir -p "$out"
  (while true; do echo "$(date -u +%FT%TZ) $(cut -d' ' -f1-3 /proc/loadavg)"; sleep 300; done) >> "$out/load.log" &
  sampler=$!
  echo "== $set ($(date -u +%FT%TZ), load $(cut -d' ' -f1-3 /proc/loadavg))"
  if [ "$set" = maps ]; then
    run_maps "$out"
  else
    sphere_checks "$SETS_DIR/$set" "$out"
    [ -s "$out/surface_standalone.jsonl" ] || surface_standalone "$SETS_DIR/$set" "$out"
    "$BIN/volmap-run" "$SETS_DIR/$set" --method map --method-args="--threads 1 --time-limit $TIME_LIMIT${MAP_ARGS:+ $MAP_ARGS}" \
      --timeout "$TIMEOUT" -j"$JOBS" --resume --out "$out" 2> "$out/progress.log" || true
    "$BIN/volmap-run" table "$out" > /dev/null
  fi
  kill "$sampler"
done
