#!/usr/bin/env bash
# Throughput of `poundbench spectrum` on the paper case set through the reference, in one
# process and shared among MPI ranks, and what the sharing costs per point.
#   scripts/mpi_throughput.sh [BUILD_DIR] [REPEATS]    (default: build, 5)
# Each configuration runs REPEATS times; the medians are printed, and written to
# reports/mpi.csv with where they were measured (reports/mpi-provenance.json), from which
# README's cluster block is regenerated (reports/make_report.py --blocks-only). The same
# configurations also run a one-point set, whose time is the fixed cost (start, MPI start,
# file writes); the rest, divided by the points, is the cost per point. CPU time (user +
# system, of mpiexec and every rank) is less sensitive to other load on the machine than
# wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
repeats=${2:-5}
pb=$build/poundbench
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # root runs mpiexec too
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

paper=cases/sets/paper.toml
one=$work/one.toml
cat > "$one" <<'TOML'
name = "one"
[[family]]
name = "one"
scene = "pair"
pulse = "sine"
directivity = "normal"
eps = 0.5
pi2 = 1
pi3 = 0.5
pi5 = 0.5
pi6 = 1
TOML
points=$("$pb" spectrum "$paper" --threads 2 | tail -n +2 | wc -l)

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# Prints "wall cpu", the medians over the repeats of one command line.
measure() {
  for _ in $(seq "$repeats"); do
    /usr/bin/time -f "%e %U %S" -o "$work/t" "$@" --out "$work/out.csv" > /dev/null
    awk '{ print $1, $2 + $3 }' "$work/t"
  done > "$work/runs"
  echo "$(cut -d' ' -f1 "$work/runs" | median) $(cut -d' ' -f2 "$work/runs" | median)"
}

/usr/bin/python3 reports/provenance.py --build-dir "$build" > "$work/provenance.json"
echo "configuration,wall_s,cpu_s,one_point_wall_s,points,points_per_s,cpu_us_per_point,repeats" > "$work/mpi.csv"
printf '%-28s %10s %10s %12s %12s\n' configuration "wall s" "cpu s" "points/s" "cpu us/point"
declare -A cpu_per_point
for config in "1 process, 1 thread" "1 process, 2 threads" "mpiexec -np 1, 1 thread" "mpiexec -np 2, 1 thread each"; do
  case $config in
    "1 process, 1 thread") cmd=("$pb" spectrum) ; threads=1 ;;
    "1 process, 2 threads") cmd=("$pb" spectrum) ; threads=2 ;;
    "mpiexec -np 1, 1 thread") cmd=(mpiexec -np 1 "$pb" spectrum) ; threads=1 ;;
    "mpiexec -np 2, 1 thread each") cmd=(mpiexec -np 2 --oversubscribe "$pb" spectrum) ; threads=1 ;;
  esac
  read -r wall cpu < <(measure "${cmd[@]}" "$paper" --threads "$threads")
  read -r wall1 cpu1 < <(measure "${cmd[@]}" "$one" --threads "$threads")
  rate=$(awk -v n="$points" -v w="$wall" -v w1="$wall1" 'BEGIN { printf "%.0f", n / (w - w1) }')
  per=$(awk -v n="$points" -v c="$cpu" -v c1="$cpu1" 'BEGIN { printf "%.1f", 1e6 * (c - c1) / n }')
  cpu_per_point[$config]=$per
  printf '%-28s %10s %10s %12s %12s   (one point: %s s wall)\n' "$config" "$wall" "$cpu" "$rate" "$per" "$wall1"
  echo "\"$config\",$wall,$cpu,$wall1,$points,$rate,$per,$repeats" >> "$work/mpi.csv"
done
awk -v a="${cpu_per_point["mpiexec -np 2, 1 thread each"]}" -v b="${cpu_per_point["1 process, 2 threads"]}" \
  'BEGIN { printf "distribution overhead: %.1f us of CPU per point (2 ranks against 1 process on 2 threads)\n", a - b }'
echo "($points points; medians of $repeats runs; $(nproc) cores)"
# Whole files or none: written only once every configuration has run.
cp "$work/mpi.csv" reports/mpi.csv.tmp && mv reports/mpi.csv.tmp reports/mpi.csv
cp "$work/provenance.json" reports/mpi-provenance.json.tmp && mv reports/mpi-provenance.json.tmp reports/mpi-provenance.json
/usr/bin/python3 reports/make_report.py --blocks-only --readme README.md
