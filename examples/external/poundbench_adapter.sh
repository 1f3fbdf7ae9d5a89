#!/bin/sh
# poundbench as an external program of itself: the second example of docs/external.md.
#
#   poundbench spectrum cases/sets/smoke.toml --solver external --steps 64 \
#       --command "sh examples/external/poundbench_adapter.sh moreau-jean"
#
# gives the rows of `--solver moreau-jean --steps 64`, Pi1 bit for bit: the case document
# carries the system exactly and `poundbench adapter` solves it with the named solver of its
# own registry. What the rows' seconds then add to the in-process run is the protocol's
# cost per point (docs/external.md, "What a point costs").
#
# The template of a wrapper around a program that is not a filter already: take the
# solver's own settings as arguments, exec the program (so that poundbench's time limit
# ends the program itself, not only this shell), and leave stdin and stdout to it.
# POUNDBENCH names the binary (default: poundbench in PATH); the arguments after the
# solver's name go to it (--variant, --theta, ...).
set -eu
solver=${1:-moreau-jean}
[ $# -gt 0 ] && shift
exec "${POUNDBENCH:-poundbench}" adapter --solver "$solver" "$@"
