#!/usr/bin/env bash
# Builds the evaluation sets of issue 15 from ../shared/data and the procedural shapes, with the
# project's own tools only. Every set is a VOLMAP layout folder that volmap-run understands
# (G<k>/<name>.mesh + G<k>_<dom>/<name>_<dom>.txt), all six domains.
#
# Usage: bench/eval/make_sets.sh <bin> <out> [set ...]
#   <bin>  a build of this branch (needs volmap-dataset --decimate/--keep-going/--coarse, volmap-shapes --thin)
#   <out>  where the sets go, e.g. /work/eval/sets (never inside the repo: the data's licences forbid it)
#   sets   any of: thin thin_coarse coarse g1sphere tetmeshes maps surfaces (default: all, in that order)
#   env    VOLMAP_DATA (default /work/shared/data), DECIMATE (default 22000 triangles),
#          STEP_TIMEOUT (seconds per surface in volmap-dataset, default 3600), MESH_PER_DOMAIN (default 1),
#          SUBDIVISIONS (volmap-shapes --subdivisions for thin and thin_coarse, 1-5, default the tool's 3)
#
# The sets (each in <out>/<set>/, with logs/<group>_<name>.json = volmap-dataset's JSON per input):
#   thin        the 16 thin-feature shapes of `volmap-shapes --thin` (group G1), TetGen p q1.414 Y
#   thin_coarse the same shapes, TetGen without q (--coarse)
#   surfaces    all 58 surfaces of shared/data/surfaces, one group per source folder (groups.tsv);
#               surfaces of more than DECIMATE triangles are decimated to DECIMATE first
#   coarse      the same 58 surfaces with --coarse (and the same decimation)
#   g1sphere    G1 of shared/data/volmap: meshes and the 5 reference maps symlinked (group G1), plus a
#               sphere map by `volmap-surface-map sphere`; when that map refines the mesh, the refined
#               mesh and its sphere map form group G2 (logs/sphere_<name>.json)
#   tetmeshes   the 8 tet meshes of shared/data/tetmeshes, flipped to the VOLMAP orientation by
#               `volmap-tetmesh-check --fix`, then mapped to the six domains by volmap-dataset
#   maps        no layout: maps.tsv lists (name, object mesh, parameter): an initial map mesh for
#               `volmap-map <object> - out --initial <parameter>`, or for the expansion_cones .ovm
#               inputs (flipped to the VOLMAP orientation by `volmap-tetmesh-check --fix`) their
#               boundary map (.txt) for `volmap-map <object> <parameter> out`; the TLC input is
#               converted to two .mesh files
# Published maps passed `volmap-surface-map-check --domain <dom>` (volmap-dataset's own check). A
# domain whose map fails is dropped and recorded in the JSON (failed_domains), the mesh it failed on
# kept as G<k>_failed/<name>_<dom>.mesh, so each set's case count is (inputs x 6) minus the
# surface-map failures. Each domain maps its own copy of the TetGen mesh (--mesh-per-domain; the
# end-to-end pipeline a user runs per case): a domain whose map split boundary edges has its mesh
# beside the map (G<k>_<dom>/<name>_<dom>.mesh), so a case's growth carries only its own splits
# (MESH_PER_DOMAIN=0: one mesh for all six domains, VOLMAP's layout, carrying all their splits).
# G<k>_unrefined/<name>.mesh is the mesh before any surface-map split.
# Deterministic: same tools, same sets (TetGen, the decimation and the surface maps are).
set -euo pipefail

[ $# -ge 2 ] || { sed -n '2,30p' "$0"; exit 2; }
source "$(dirname "$0")/common.sh"
BIN=$(absolute_dir "$1")
OUT=$(absolute_dir "$2")
shift 2
SETS=("${@:-${ALL_SETS[@]}}")
DATA=${VOLMAP_DATA:-/work/shared/data}
DECIMATE=${DECIMATE:-22000}
STEP_TIMEOUT=${STEP_TIMEOUT:-3600}
PER_DOMAIN_FLAG=$([ "${MESH_PER_DOMAIN:-1}" = 0 ] || echo --mesh-per-domain)
DOMAINS=cube,tet,pyr,octa,star,sphere
SOURCES=(cgal cinolib common3d gmsh libigl_tutorial nightmare_of_polycubes)  # surfaces: group G1..G6

# dataset_one <set_dir> <group> <input file> [volmap-dataset options...]
# One input through volmap-dataset (alone, so a hang or crash costs only that input); its JSON goes to
# <set_dir>/logs/<group>_<name>.json.
dataset_one() {
  local set_dir=$1 group=$2 input=$3
  shift 3
  local name stage log rc=0
  name=$(basename "${input%.*}")
  log="$set_dir/logs/${group}_$name.json"
  if [ -s "$log" ]; then return 0; fi  # done in an earlier run
  stage=$(mktemp -d)
  ln -s "$(realpath "$input")" "$stage/"
  mkdir -p "$set_dir/logs"
  timeout "$STEP_TIMEOUT" "$BIN/volmap-dataset" "$stage" "$set_dir" --group "$group" --domains "$DOMAINS" \
    --keep-going --keep-unrefined $PER_DOMAIN_FLAG --json "$@" > "$log.tmp" 2> "$set_dir/logs/${group}_$name.err" || rc=$?
  if [ "$rc" = 124 ]; then
    echo "{\"ok\":false,\"surfaces\":[{\"name\":\"$name\",\"added\":false,\"reason\":\"volmap-dataset timed out after $STEP_TIMEOUT s\"}]}" > "$log.tmp"
  elif ! [ -s "$log.tmp" ]; then
    echo "{\"ok\":false,\"surfaces\":[{\"name\":\"$name\",\"added\":false,\"reason\":\"volmap-dataset exit $rc\"}]}" > "$log.tmp"
  fi
  mv "$log.tmp" "$log"
  rm -rf "$stage" "$set_dir/.work_$group"
  echo "  $group/$name: $(python3 -c 'import json,sys; s=json.load(open(sys.argv[1]))["surfaces"][0]; print("added" if s.get("added") else "skipped: "+s.get("reason","")[:150], *["%s failed" % f["domain"] for f in s.get("failed_domains",[])])' "$log")"
}

make_thin() {  # <set> [--coarse]
  local set_dir=$OUT/$1
  shift
  mkdir -p "$set_dir"
  "$BIN/volmap-shapes" "$set_dir/surfaces" --thin --format off ${SUBDIVISIONS:+--subdivisions "$SUBDIVISIONS"} > /dev/null
  for s in "$set_dir"/surfaces/*.off; do dataset_one "$set_dir" G1 "$s" "$@"; done
}

make_surfaces() {  # <set> [--coarse]
  local set_dir=$OUT/$1 k=0
  shift
  mkdir -p "$set_dir"
  : > "$set_dir/groups.tsv"
  for src in "${SOURCES[@]}"; do
    k=$((k + 1))
    printf 'G%d\t%s\n' "$k" "$src" >> "$set_dir/groups.tsv"
    for s in "$DATA/surfaces/$src"/*; do dataset_one "$set_dir" "G$k" "$s" --decimate "$DECIMATE" "$@"; done
  done
}

make_g1sphere() {
  local set_dir=$OUT/g1sphere name r rc
  mkdir -p "$set_dir/G1" "$set_dir/G1_sphere" "$set_dir/logs"
  for dom in cube tet pyr octa star; do
    mkdir -p "$set_dir/G1_$dom"
    for m in "$DATA"/volmap/G1_$dom/*.txt; do ln -sf "$m" "$set_dir/G1_$dom/"; done
  done
  for mesh in "$DATA"/volmap/G1/*.mesh; do
    name=$(basename "$mesh" .mesh)
    ln -sf "$mesh" "$set_dir/G1/"
    [ -s "$set_dir/logs/sphere_$name.json" ] && continue
    r=$(mktemp -d)
    rc=0
    "$BIN/volmap-surface-map" sphere "$mesh" "$r/map.txt" --refined "$r/refined.mesh" --json \
      > "$set_dir/logs/sphere_$name.json" 2> "$set_dir/logs/sphere_$name.err" || rc=$?
    if [ "$rc" = 0 ] && [ -f "$r/refined.mesh" ]; then
      mkdir -p "$set_dir/G2" "$set_dir/G2_sphere"
      mv "$r/refined.mesh" "$set_dir/G2/$name.mesh"
      mv "$r/map.txt" "$set_dir/G2_sphere/${name}_sphere.txt"
    elif [ "$rc" = 0 ]; then
      mv "$r/map.txt" "$set_dir/G1_sphere/${name}_sphere.txt"
    fi
    rm -rf "$r"
    echo "  g1sphere/$name: exit $rc"
  done
}

make_tetmeshes() {
  local set_dir=$OUT/tetmeshes f name
  mkdir -p "$set_dir/inputs"
  for f in "$DATA"/tetmeshes/*/*; do
    name=$(basename "${f%.*}")
    [ -f "$set_dir/inputs/$name.mesh" ] ||
      "$BIN/volmap-tetmesh-check" "$f" --fix "$set_dir/inputs/$name.mesh" --json > "$set_dir/inputs/$name.fix.json" || true
  done
  for f in "$set_dir"/inputs/*.mesh; do dataset_one "$set_dir" G1 "$f"; done
}

# TLC's text input (nV 3 / rest, nV 3 / initial, nT 4 / tets, nH / handles; 0-based) -> two Medit files.
tlc_to_medit() {
  python3 - "$1" "$2" "$3" <<'EOF'
import sys
tok = open(sys.argv[1]).read().split()
i = 0
def block(cols):
    global i
    n, c = int(tok[i]), int(tok[i + 1]); i += 2
    assert c == cols
    rows = [tok[i + k * c:i + (k + 1) * c] for k in range(n)]; i += n * c
    return rows
rest, init, tets = block(3), block(3), block(4)
for path, xyz in ((sys.argv[2], rest), (sys.argv[3], init)):
    with open(path, "w") as f:
        f.write("MeshVersionFormatted 1\nDimension 3\nVertices\n%d\n" % len(xyz))
        f.writelines("%s %s %s 0\n" % tuple(p) for p in xyz)
        f.write("Tetrahedra\n%d\n" % len(tets))
        f.writelines("%d %d %d %d 0\n" % tuple(int(v) + 1 for v in t) for t in tets)
        f.write("End\n")
EOF
}

make_maps() {
  local set_dir=$OUT/maps m name
  mkdir -p "$set_dir/tlc"
  printf 'name\tobject\tparameter\tnote\n' > "$set_dir/maps.tsv"
  for m in "$DATA"/maps/galaxymaps/*_object.vtk; do
    name=$(basename "$m" _object.vtk)
    printf 'galaxymaps_%s\t%s\t%s\t\n' "$name" "$m" "${m%_object.vtk}_parameter.vtk" >> "$set_dir/maps.tsv"
  done
  printf 'lim_armadillo-598\t%s\t%s\t\n' "$DATA/maps/lim_benchmark/armadillo-598-rest.vtk" \
    "$DATA/maps/lim_benchmark/armadillo-598-init.vtk" >> "$set_dir/maps.tsv"
  tlc_to_medit "$DATA/maps/tlc/input" "$set_dir/tlc/rest.mesh" "$set_dir/tlc/init.mesh"
  printf 'tlc_cube\t%s\t%s\t\n' "$set_dir/tlc/rest.mesh" "$set_dir/tlc/init.mesh" >> "$set_dir/maps.tsv"
  mkdir -p "$set_dir/expansion_cones"
  for m in "$DATA"/maps/expansion_cones/*_domain.ovm; do
    name=$(basename "$m" _domain.ovm)
    # OpenVolumeMesh orders tets the other way: flipped to the VOLMAP convention first.
    "$BIN/volmap-tetmesh-check" "$m" --fix "$set_dir/expansion_cones/$name.mesh" --json \
      > "$set_dir/expansion_cones/$name.fix.json" || true
    printf 'expansion_cones_%s\t%s\t%s\t\n' "$name" "$set_dir/expansion_cones/$name.mesh" \
      "$(ls "$DATA"/maps/expansion_cones/"${name}"_*_boundary.txt)" >> "$set_dir/maps.tsv"
  done
}

for set in "${SETS[@]}"; do
  echo "== $set ($(date -u +%FT%TZ))"
  case $set in
    thin) make_thin thin ;;
    thin_coarse) make_thin thin_coarse --coarse ;;
    surfaces) make_surfaces surfaces ;;
    coarse) make_surfaces coarse --coarse ;;
    g1sphere) make_g1sphere ;;
    tetmeshes) make_tetmeshes ;;
    maps) make_maps ;;
    *) echo "unknown set '$set'" >&2; exit 2 ;;
  esac
done
