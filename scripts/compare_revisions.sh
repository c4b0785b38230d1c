#!/usr/bin/env bash
# Before/after speed of both engines in one run (two git revisions, the same clouds, interleaved
# rounds): see scripts/compare_revisions.py. Needs scripts/setup.sh to have run.
#   scripts/compare_revisions.sh BEFORE [AFTER] [--rounds N] [--points N] [--shapes sphere,torus]
#                                [--filters g2s,spherepack] [--clouds A.ply,B.ply]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
exec python3 scripts/compare_revisions.py "$@"
