#!/bin/sh
# Re-runs every hostile case of issue 15 against a build and prints one PASS/FAIL row per case
# (docs/reliability.md, "Hostile cases"). Exit 0 when all pass.
#   tests/reliability/hostile/run.sh [BUILD_DIR] [--group NAME ...] [--keep]
# BUILD_DIR (default: build) must be configured; the two targets it needs, gale and
# gale_full_disk_shim, are brought up to date first.
set -e
here=$(cd "$(dirname "$0")" && pwd)
build=build
case "$1" in -*|"") ;; *) build=$1; shift ;; esac
cmake --build "$build" -j2 --target gale gale_full_disk_shim >/dev/null
exec python3 "$here/run.py" "$build" "$@"
