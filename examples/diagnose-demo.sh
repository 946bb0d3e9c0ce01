#!/bin/sh
# The diagnose demo of the README: CMM profiles of four O2005 arc parts (thesis Appendix A)
# made at minutes 0, 30, 60 and 120 on a truth machine at the thesis' magnitudes
# (examples/machines/thesis-truth.toml), diagnosed against a working model that lacks the
# Z ball screw's cyclic error (thesis-working.toml). Also a ball bar trace of the thesis'
# 100 mm bar on the same machine. Run from the repository root.
set -eu
turnpass=${TURNPASS:-target/release/turnpass}
[ -x "$turnpass" ] || cargo build --release
machines=examples/machines
data=examples/data

"$turnpass" synth examples/programs/thesis-o2005-arc.nc --model $machines/thesis-truth.toml --kind profile \
    --noise 0.0002 --seed 2005 --parts 0,30,60,120 -o $data/o2005-cmm.csv
"$turnpass" diagnose examples/programs/thesis-o2005-arc.nc --model $machines/thesis-working.toml \
    --measured $data/o2005-cmm.csv --write-model $machines/thesis-diagnosed.toml --plot $data/o2005-diagnose.svg \
    > $data/o2005-diagnose.txt

"$turnpass" synth examples/programs/ballbar-r100.nc --model $machines/thesis-truth.toml --kind ballbar \
    --noise 0.0002 --seed 100 -o $data/ballbar-r100.csv
"$turnpass" diagnose examples/programs/ballbar-r100.nc --model $machines/thesis-working.toml \
    --measured $data/ballbar-r100.csv --plot $data/ballbar-r100-diagnose.svg > $data/ballbar-r100-diagnose.txt
