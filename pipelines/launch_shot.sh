#!/bin/sh
# usage: launch_shot.sh "LAUNCHER" UHPC_MACRO ARGS...
# Starts one shot (uhpc-macro with --out, as the make rules write it) through a launcher such as Slurm's
# "srun -N1 -n1 -c2 --exclusive", unless --out already holds a finished run of the same inputs: that is
# asked here first (uhpc-macro --reuse-check, a second's work, no job step), so a resumed study spends a
# job step only on the shots it still needs. A run of other inputs stops it (uhpc-macro's exit 2).
launcher=$1
shift
verdict=$("$@" --reuse-check -q) || exit $?
[ "$verdict" = kept ] && exit 0
# The launcher is split as the shell splits words, as the make rules do with LAUNCH.
# shellcheck disable=SC2086
exec $launcher "$@"
