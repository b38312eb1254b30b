#!/bin/sh
# hold_lock.sh LOCK_FILE PROGRAM ARGS...
# Runs PROGRAM while holding LOCK_FILE's flock with a holder record in it, as a run of the programs holds
# its output (uhpc/output_lock.hpp): the second writer's side of the output lock, end to end. The record
# is fixed so that the refusal's message is exact.
set -e
lock=$1
shift
mkdir -p "$(dirname "$lock")"
printf 'pid 4242 (a test holding the lock) on host ctest since 2026-12-06T16:00:00Z\n' > "$lock"
exec flock --nonblock "$lock" "$@"
