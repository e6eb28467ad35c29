#!/bin/sh
# Re-check the hostile inputs (huge sizes, devices, escaping names, …) against a release build: one Markdown table row per
# input (exit code, wall time, first line of the answer). Run from the repository root
# after `cargo build --release`; writes only into a temporary folder it removes.
set -u
BIN=${BIN:-target/release/rockslide}
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
row() { # row LABEL CMD... : run CMD with a 60 s limit, print the row
    label=$1; shift
    start=$(date +%s.%N)
    timeout 60 "$@" >"$T/out" 2>"$T/err"; code=$?
    secs=$(echo "$(date +%s.%N) - $start" | bc)
    first=$(cat "$T/err" "$T/out" | grep -v '^\s*$' | head -1 | sed "s|$T|<tmp>|g; s|$PWD/||g; s/|/\\\\|/g" | cut -c1-150)
    printf '| %s | %s | %.2f s | %s |\n' "$label" "$code" "$secs" "$first"
}
edit() { # edit CASE FROM TO NEW : a shipped case with FROM replaced by TO, as NEW
    sed "s|$2|$3|" "cases/$1.toml" >"$T/$4"
}
echo '| input | exit | time | answer (first line) |'
echo '|---|---|---|---|'
at2() { printf 'T\nE\nACCELERATION TIME HISTORY IN UNITS OF G\nNPTS= %s, DT= %s SEC\n%s\n' "$1" "$2" "$3" >"$T/$4"; }
at2 1e19 0.01 '0.1 0.2' npts19.AT2;  row 'AT2 `NPTS= 1e19`' "$BIN" newmark "$T/npts19.AT2" --ky 0.1
at2 1e12 0.01 '0.1 0.2' npts12.AT2;  row 'AT2 `NPTS= 1e12`' "$BIN" newmark "$T/npts12.AT2" --ky 0.1
at2 2 1e-300 '0.1 0.2' dt300.AT2;   row 'AT2 `DT= 1e-300`, two values' "$BIN" newmark "$T/dt300.AT2" --ky 0.1
edit linear-sdof 'dt = 0.001$' 'dt = 1e-12' dt12.toml
row 'case `dt = 1e-12`' "$BIN" run "$T/dt12.toml" -q -o "$T/o1"
row '`reference --dt 1e-12`' "$BIN" reference cases/linear-sdof.toml --dt 1e-12 -o "$T/r.csv"
sed "s|base = \"\\.\\./|base = \"$PWD/|; s|\"\\.\\./cases|\"$PWD/cases|g; s|^tail = 5.0|tail = 1e6|" studies/pepo-records.toml >"$T/grid.toml"
row 'study `tail = 1e6`' "$BIN" study "$T/grid.toml" -q -o "$T/o2"
row '`sweep --rungs 64`' "$BIN" sweep cases/linear-sdof.toml --rungs 64 -q -o "$T/o3"
row '`sweep --ratio 1e300`' "$BIN" sweep cases/linear-sdof.toml --ratio 1e300 -q -o "$T/o3"
for f in fuzz/regressions/mcap_read/*; do row "MCAP: fuzz crash input $(basename "$f" | cut -c1-12)" "$BIN" trace-info "$f"; done
"$BIN" run cases/linear-sdof.toml -q -o "$T/m" >/dev/null 2>&1
M=$(find "$T/m" -name '*.mcap' | head -1)
python3 -c "import sys;b=bytearray(open(sys.argv[1],'rb').read());b[len(b)//2]^=0xff;open(sys.argv[2],'wb').write(b)" "$M" "$T/flip.mcap"
row 'MCAP: one byte flipped (middle)' "$BIN" trace-info "$T/flip.mcap"
edit records/pepo-loma-prieta 'record = "Loma_Prieta_1989_HSP-000.AT2"' 'record = "/dev/zero"' devzero.toml
sed -i 's|^record = "/dev/zero".*|record = "/dev/zero"\nrecord_unit = "g"|' "$T/devzero.toml"
cp cases/records/*.AT2 "$T/" 2>/dev/null
row 'case `record = "/dev/zero"`' "$BIN" run "$T/devzero.toml" -q -o "$T/o4"
printf 'base = "%s/cases/records/pepo-loma-prieta.toml"\nrecords = [{ path = "/dev/zero", unit = "g" }]\n' "$PWD" >"$T/grid0.toml"
row 'study grid `records = ["/dev/zero"]`' "$BIN" study "$T/grid0.toml" -q -o "$T/o5"
edit pepo-mass-accel 'mass = 1.0e6' 'mass = 1e-300' mass.toml
row 'reference, `mass = 1e-300`' "$BIN" reference "$T/mass.toml" -o "$T/r1.csv"
edit pepo-mass-accel 'kx = 9.8696e8' 'kx = 1e300' kx.toml
row 'reference, `kx = 1e300`' "$BIN" reference "$T/kx.toml" -o "$T/r2.csv"
edit pepo-mass-accel 'omega = 15.707963267948966' 'omega = 1e9' omega.toml
row 'reference, pulse `ω = 1e9`' "$BIN" reference "$T/omega.toml" -o "$T/r3.csv"
row '`stability -j 100000` (mu-zero)' "$BIN" stability cases/stability/mu-zero.toml -j 100000 -q -o "$T/o6"
for n in '../escaped' "$T/abs" '' '.' 'summary.csv'; do
    printf 'name = "%s"\n' "$n" >"$T/named.toml"; cat cases/linear-sdof.toml >>"$T/named.toml"
    row "\`name = \"$(echo "$n" | sed "s|$T|<tmp>|")\"\`" "$BIN" run "$T/named.toml" -q -o "$T/o7/out"
done
printf '| (nothing written outside `-o`: %s) | | | |\n' "$(ls "$T" | grep -c -e escaped -e abs) entries"
edit pepo-mass-accel '^\[engines.predictor-corrector\]' '[engines.predictor-corrector]\nfrobnicate = 1' pcunk.toml
row 'unknown key under `[engines.predictor-corrector]`' "$BIN" run "$T/pcunk.toml" -q -o "$T/o8"
edit linear-sdof 'kind = "mass-acceleration"' 'kind = "none"' none.toml
sed -i 's|^amplitude = 1.0$|amplitude = nan|' "$T/none.toml"
row '`kind = "none"`, `amplitude = nan`' "$BIN" run "$T/none.toml" -q -o "$T/o9"
printf '0,0.1\n1e-300,0.2\n' >"$T/tiny.csv"
row 'CSV record, time step 1e-300' "$BIN" newmark "$T/tiny.csv" --ky 0.1 --unit g
edit pepo-mass-accel 'variants = \["single", "double"\]' 'variants = ["single", "single"]' dup.toml
row 'a variant named twice' "$BIN" run "$T/dup.toml" -q -o "$T/o10"
edit pepo-mass-accel 'variants = \["single", "double"\]' 'variants = ["single", "no-such"]' badvar.toml
row '`list` with an unknown variant' "$BIN" list "$T/badvar.toml"
row '`reference` with an unknown variant' "$BIN" reference "$T/badvar.toml" -o "$T/r4.csv"
row 'negative option `--dt -1`' "$BIN" reference cases/linear-sdof.toml --dt -1 -o "$T/r5.csv"
printf 'title = "\377\376"\n' >"$T/latin.toml"
row 'non-UTF-8 case file' "$BIN" run "$T/latin.toml" -q -o "$T/o11"
mkdir -p "$T/o12/linear-sdof"; head -c 2000000 /dev/urandom >"$T/o12/linear-sdof/.x.csv.rockslide-tmp"; touch -d '2 hours ago' "$T/o12/linear-sdof/.x.csv.rockslide-tmp"
row 'stale hidden temporary in the output folder' "$BIN" run cases/linear-sdof.toml -q -o "$T/o12"
printf '| (stale temporaries left: %s) | | | |\n' "$(find "$T/o12" -name '*.rockslide-tmp' | wc -l)"
edit rpepo-mass-accel 'integrator = "hht"' 'integrator = "newmark"\nkinematics = "exact"\nrotational_inertia = 10.0\ndt = 1e-4' rp.toml
sed -i 's|^alpha = -0.1$||' "$T/rp.toml"
row 'fe double, exact kinematics, Newmark, I = 10, Δt = 1e-4 (RPEPO)' "$BIN" run "$T/rp.toml" -q -o "$T/o13"
python3 -c "import json,sys;r=json.load(open(sys.argv[1]));print('| (fe runs: '+'; '.join(x['variant']+' '+str(x['outcome'])+' '+str(x['stats']) for x in r['runs'] if x['engine']=='fe')+') | | | |')" "$T/o13/rp/result.json"
