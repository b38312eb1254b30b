#!/bin/bash
# `cmake --install` gives a copy that runs anywhere: the programs find the shipped data beside them
# (<prefix>/share/uhpc_multiscale/data), answer --version, and the installed pipelines use the
# installed programs and build nothing.
# usage: check_install.sh BUILD_DIR SCRATCH_DIR
set -euo pipefail
build=$1
scratch=$2
rm -rf "$scratch"
mkdir -p "$scratch/elsewhere"
cmake --install "$build" --prefix "$scratch/prefix" > "$scratch/install.log"
prefix=$scratch/prefix
share=$prefix/share/uhpc_multiscale
for p in uhpc-micro uhpc-calibrate uhpc-sdel uhpc-macro uhpc-compare-shots; do
  "$prefix/bin/$p" --version | grep -q "^$p [0-9]" || { echo "$p --version"; exit 1; }
done
for f in data/table5_ballistic_experiments.csv data/calibrate.json pipelines/Makefile LICENSE README.md; do
  [ -e "$share/$f" ] || { echo "missing $share/$f"; exit 1; }
done
cd "$scratch/elsewhere"
# The default config of synthesize is found in the installed data, not in the sources.
env -u UHPC_DATA_DIR "$prefix/bin/uhpc-calibrate" synthesize --sdel "$share/data/sdel_paper.json" --out ens.h5 > synth.log
[ -s ens.h5 ] || { echo "synthesize wrote nothing"; exit 1; }
# The installed pipelines run the installed programs and build nothing.
make -n -C "$share/pipelines" shots OUT="$scratch/out" > make.log
grep -q "^$prefix/bin/uhpc-macro --config $share/data/macro_disc_afc.json" make.log || { cat make.log; exit 1; }
if grep -q "cmake" make.log; then echo "the installed pipelines try to build"; cat make.log; exit 1; fi
echo "install: programs, data and pipelines in $prefix work from $scratch/elsewhere"
