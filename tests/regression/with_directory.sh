#!/bin/sh
# with_directory.sh DIR PROGRAM ARGS...
# Makes DIR (with its parents), then runs PROGRAM: an output whose path a directory is in the way of.
set -e
mkdir -p "$1"
shift
exec "$@"
