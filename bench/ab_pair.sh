#!/usr/bin/env bash
# Compares two builds of the `collide` command on one scene, on a shared host whose speed drifts by
# tens of percent from minute to minute: each round runs both at the same time, one per core
# (taskset; the cores swapped every round), so both see the same host, and the round's ratio
# new / base cancels the drift. Prints each round's ratio and their median.
#
#   bench/ab_pair.sh BASE_COLLIDE NEW_COLLIDE [SCENE=terrain] [ROUNDS=10] [STEPS=600]
#
# Both binaries run `collide bench SCENE --runs 1 --steps STEPS` (CPU ms per step). The two share
# the L3 cache and the memory bandwidth while they run, so a change that saves memory traffic shows
# here at least as much as alone. Needs two cores.
set -euo pipefail
base=${1:?base collide binary}
new=${2:?new collide binary}
scene=${3:-terrain}
rounds=${4:-10}
steps=${5:-600}
ratios=()
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
msPerStep() { awk '/^median:/ {print $2}' "$1"; }
for ((round = 1; round <= rounds; ++round)); do
  if ((round % 2)); then baseCore=0 newCore=1; else baseCore=1 newCore=0; fi
  taskset -c "$baseCore" "$base" bench "$scene" --runs 1 --steps "$steps" > "$tmp/base" &
  taskset -c "$newCore" "$new" bench "$scene" --runs 1 --steps "$steps" > "$tmp/new"
  wait
  b=$(msPerStep "$tmp/base") n=$(msPerStep "$tmp/new")
  ratio=$(awk -v b="$b" -v n="$n" 'BEGIN {printf "%.3f", n / b}')
  echo "round $round: base $b ms/step, new $n ms/step, new/base $ratio"
  ratios+=("$ratio")
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{v[NR] = $1} END {m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2; printf "median new/base over %d rounds: %.3f\n", NR, m}'
