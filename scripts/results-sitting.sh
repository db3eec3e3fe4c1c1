#!/usr/bin/env bash
# One sitting of every figure on docs/benchmarks.md: each command alone on the second core, into
# results/page/<scenario>/. Then scripts/results-page.py prints the page's tables from them.
#   scripts/results-sitting.sh [DATA_DIR]   (default ../shared/data; the simulator's drive is made once)
set -euo pipefail
cd "$(dirname "$0")/.."
data=${1:-../shared/data}
eco=build/bin/eco
out=results/page
sim=build/sim-default
test -f $sim/poses.txt || $eco simulate --out $sim --frames 120 --seed 1 > /dev/null
run() { local name=$1; shift; echo "== $name: eco bench $*" >&2; rm -rf $out/$name; taskset -c 1 $eco bench "$@" --out $out/$name > /dev/null; }
sequences=()
for d in $data/*/; do test -f "$d/poses.txt" && sequences+=("$(basename "$d")"); done
for p in robot robot-cap-0.2 robot-cap-0.1; do
  for s in "${sequences[@]}" sim; do
    dir=$data/$s; [ $s = sim ] && dir=$sim
    # BALM uncapped grows past a million points, which nanoflann and octree_base rebuild every frame
    [ $p = robot ] && [[ $s = balm* ]] && continue
    run $s-$p --data $dir --preset $p --methods eco,octree_base,nanoflann,pcl_octree,scan_pass
  done
done
for s in "${sequences[@]}" sim; do
  dir=$data/$s; [ $s = sim ] && dir=$sim
  run $s-clearing --data $dir --preset robot-cap-0.1 --methods eco,eco_clearing --knn-queries 0
done
# the paper's Table II on its own data (the KITTI minis) and the simulator; BALM's aggregated map is
# past a million points in the box, which the rebuilding baselines take minutes a frame over
paper=eco,eco_exact,octree_base,ioctree_global,ioctree_target,nanoflann,pcl_octree
for s in "${sequences[@]}" sim; do
  [[ $s = balm* ]] && continue
  dir=$data/$s; [ $s = sim ] && dir=$sim
  run $s-paper-static --data $dir --preset paper --workload static --frames 60 --methods $paper
  run $s-paper-dynamic --data $dir --preset paper --workload dynamic --methods $paper
done
