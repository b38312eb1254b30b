#!/usr/bin/env bash
# The speed peer of the macro benchmark: runs a LAMMPS deck (default the bond-based peridynamics disc,
# macro/bench/lammps-uhpc-disc.in) with 1 process (`lmp -in deck`) and with 2 processes
# (`mpirun --allow-run-as-root -np 2 lmp -in deck`), each in its own scratch directory under
# <out>/lammps/np<P>/ (the deck's copy, screen.txt, log.lammps), reads LAMMPS's
#   Loop time of T on P procs for N steps with A atoms
# and writes <out>/lammps.json: the LAMMPS version line, the load average, and per process count the
# atoms, steps, loop time, particle-steps/s = A N / T and LAMMPS's "% CPU use" (below 100 on a shared
# machine) (read by pipelines/bench_ratio.py).
#
#   bash pipelines/bench_lammps.sh [--deck FILE] [--out DIR]      (make -C pipelines bench-lammps)
#
# Exit 0 on success, 2 when lmp or mpirun is missing or the input is bad (one line saying why), 1 when a
# LAMMPS run fails or prints no loop time. LMP and MPIRUN override the programs.
set -euo pipefail

deck="$(cd "$(dirname "$0")/.." && pwd)/macro/bench/lammps-uhpc-disc.in"
out=out/bench
while [ $# -gt 0 ]; do
  case "$1" in
    --deck) deck="${2:?--deck needs a file}"; shift 2 ;;
    --out) out="${2:?--out needs a directory}"; shift 2 ;;
    -h|--help) awk 'NR > 1 && !/^#/ {exit} NR > 1 {sub(/^# ?/, ""); print}' "$0"; exit 0 ;;
    *) echo "bench_lammps: unknown option '$1' (known: --deck FILE, --out DIR)" >&2; exit 2 ;;
  esac
done

lmp="${LMP:-lmp}"
mpirun="${MPIRUN:-mpirun}"
if ! command -v "$lmp" >/dev/null 2>&1; then
  echo "bench_lammps: LAMMPS ('$lmp') is not on PATH; install it with: bash pipelines/install-deps.sh --with-lammps" >&2
  exit 2
fi
if ! command -v "$mpirun" >/dev/null 2>&1; then
  echo "bench_lammps: '$mpirun' is not on PATH (Open MPI, for the 2-process run); install it with: bash pipelines/install-deps.sh" >&2
  exit 2
fi
if [ ! -r "$deck" ]; then
  echo "bench_lammps: $deck: cannot read the LAMMPS deck (give another with --deck FILE, or LAMMPS_DECK=... to make)" >&2
  exit 2
fi

mkdir -p "$out"
out="$(cd "$out" && pwd)"
deck="$(cd "$(dirname "$deck")" && pwd)/$(basename "$deck")"
scratch="$out/lammps"
cores="$(env -u OMP_NUM_THREADS nproc 2>/dev/null || echo null)"  # GNU nproc honours OMP_NUM_THREADS
load_average() { cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo unknown; }
load="$(load_average)"
# One MPI rank = one core; LAMMPS's own OpenMP styles are not used by the deck.
export OMP_NUM_THREADS=1

json_string() { printf '%s' "$1" | sed -e 's/\\/\\\\/g' -e 's/"/\\"/g'; }

version=""
runs=()
for np in 1 2; do
  dir="$scratch/np$np"
  rm -rf "$dir"
  mkdir -p "$dir"
  cp "$deck" "$dir/deck.in"
  if [ "$np" -eq 1 ]; then
    cmd=("$lmp" -in deck.in)
  else
    cmd=("$mpirun" --allow-run-as-root -np "$np" "$lmp" -in deck.in)
  fi
  echo "bench_lammps: $np process(es): (cd $dir && ${cmd[*]})"
  if ! (cd "$dir" && "${cmd[@]}" >screen.txt 2>&1); then
    echo "bench_lammps: the $np-process run failed; see $dir/screen.txt" >&2
    tail -n 5 "$dir/screen.txt" >&2 || true
    exit 1
  fi
  # "Loop time of 12.3456 on 2 procs for 100 steps with 158500 atoms" (the last run of the deck)
  loop="$(grep -E '^Loop time of [^ ]+ on [0-9]+ procs.* for [0-9]+ steps with [0-9]+ atoms' "$dir/screen.txt" | tail -n 1 || true)"
  if [ -z "$loop" ]; then
    echo "bench_lammps: no 'Loop time of ...' line in $dir/screen.txt" >&2
    exit 1
  fi
  read -r t procs steps atoms < <(echo "$loop" |
    sed -E 's/^Loop time of ([^ ]+) on ([0-9]+) procs.* for ([0-9]+) steps with ([0-9]+) atoms.*/\1 \2 \3 \4/')
  if [ "$procs" -ne "$np" ]; then
    echo "bench_lammps: asked for $np processes but LAMMPS ran on $procs ($dir/screen.txt)" >&2
    exit 1
  fi
  # "96.9% CPU use with 1 MPI tasks x 1 OpenMP threads": below 100 % the machine was shared
  cpu="$(sed -nE 's/^([0-9.]+)% CPU use with .*/\1/p' "$dir/screen.txt" | tail -n 1)"
  rate="$(awk -v a="$atoms" -v n="$steps" -v t="$t" 'BEGIN { if (t > 0) printf "%.1f", a * n / t; else print "null" }')"
  [ -n "$version" ] || version="$(grep -m1 -E '^LAMMPS \(' "$dir/screen.txt" || true)"
  echo "bench_lammps: $np process(es): $atoms atoms x $steps steps in $t s = $rate particle-steps/s (CPU use ${cpu:-?} %)"
  runs+=("    {\"processes\": $np, \"atoms\": $atoms, \"steps\": $steps, \"loop_time_s\": $t, \"particle_steps_per_s\": $rate, \"cpu_use_percent\": ${cpu:-null}}")
done

{
  echo "{"
  echo "  \"program\": \"LAMMPS\","
  echo "  \"version\": \"$(json_string "$version")\","
  echo "  \"deck\": \"$(json_string "$deck")\","
  echo "  \"host_cores\": $cores,"
  echo "  \"load_average_1min_at_start\": \"$(json_string "$load")\","
  echo "  \"load_average_1min_at_end\": \"$(json_string "$(load_average)")\","
  echo "  \"runs\": ["
  for i in "${!runs[@]}"; do
    if [ "$i" -lt $((${#runs[@]} - 1)) ]; then echo "${runs[$i]},"; else echo "${runs[$i]}"; fi
  done
  echo "  ]"
  echo "}"
} >"$out/lammps.json.tmp"
mv "$out/lammps.json.tmp" "$out/lammps.json"
echo "bench_lammps: $out/lammps.json (runs in $scratch/)"
