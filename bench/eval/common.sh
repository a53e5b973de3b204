# Sourced by bench/eval/make_sets.sh and run_sets.sh: the sets in build / measure order (most
# informative first) and `absolute_dir <dir>` (created when missing, printed absolute).
ALL_SETS=(thin thin_coarse coarse g1sphere tetmeshes maps surfaces)
absolute_dir() { mkdir -p "$1" && (cd "$1" && pwd); }
