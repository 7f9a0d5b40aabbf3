#!/usr/bin/env bash
# Acceptance 7 (issue 2): the command line runs a case and rejects bad options with exit code 2
# and a message naming the culprit. Usage: test_cli.sh PATH/TO/exasph
set -u
exe=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# A real run prints the header, five step rows and the summary, and exits 0.
out=$("$exe" --init square-patch -n 20 -s 5 --out "$work/run" 2>&1)
rc=$?
[ $rc -eq 0 ] || fail "run exited $rc: $out"
echo "$out" | grep -q "8000 particles" || fail "header lacks the particle count"
[ "$(echo "$out" | grep -cE '^ +[1-5] [0-9.e+-]+ ')" -eq 5 ] || fail "expected 5 step rows: $out"
echo "$out" | grep -q "particle-steps/s" || fail "no summary"
[ "$(wc -l < "$work/run/diagnostics.csv")" -eq 6 ] || fail "diagnostics.csv should have 6 lines"

# The formulation (issue 16): each case's default scheme, printed in the header; options given
# beside a scheme keep their values.
header() { "$exe" "$@" -s 0 --lattice --out "$work/scheme" 2>&1 | grep '^physics:'; }
h=$(header --init square-patch -n 8)
echo "$h" | grep -q "scheme wc, ng0 250, ngmax 375,.*conductivity 0, av_limiter off, volume_elements off, energy_weights off, tensile_stress 0.3, tensile_exponent 6, tensile_stress_positive 0.03, torque_free on, double_precision on" ||
    fail "square-patch should default to the wc scheme: $h"
h=$(header --init square-patch -n 8 --scheme std)
echo "$h" | grep -q "scheme std, ng0 100, ngmax 150,.*volume_elements off, energy_weights off, tensile_stress 0, tensile_exponent 4, tensile_stress_positive 0, torque_free off, double_precision off" ||
    fail "--scheme std for square-patch: $h"
h=$(header --init sedov -n 8)
echo "$h" | grep -q "scheme ve,.*conductivity 1, av_limiter on, volume_elements on, energy_weights off" ||
    fail "sedov should default to the ve scheme: $h"
h=$(header --init isobaric-cube -n 8)
echo "$h" | grep -q "scheme pe, ng0 200, ngmax 300,.*conductivity 0, av_limiter on, volume_elements on, energy_weights on" ||
    fail "isobaric-cube should default to the pe scheme: $h"
for c in kelvin-helmholtz wind-cloud; do
    h=$(header --init $c -n 16)
    echo "$h" | grep -q "scheme sh, ng0 100, ngmax 150,.*av_switch on,.*conductivity 0, av_limiter on, volume_elements on, energy_weights off" ||
        fail "$c should default to the sh scheme: $h"
done
h=$(header --init sedov -n 8 --scheme std)
echo "$h" | grep -q "scheme std,.*conductivity 0, av_limiter off, volume_elements off" ||
    fail "--scheme std: $h"
h=$(header --init sedov -n 8 --conductivity 0.5)
echo "$h" | grep -q "scheme ve,.*conductivity 0.5, av_limiter on" ||
    fail "--conductivity beside the ve scheme should keep its value: $h"

# Bad input: exit code 2 and one line naming the option.
expect_rejected() { # NAME_IN_MESSAGE ARGS...
    local needle=$1
    shift
    local msg
    msg=$("$exe" "$@" --out "$work/bad" 2>&1 >/dev/null)
    local rc=$?
    [ $rc -eq 2 ] || fail "'$*' exited $rc, expected 2"
    echo "$msg" | grep -q -- "$needle" || fail "'$*' message does not name '$needle': $msg"
    [ "$(echo "$msg" | wc -l)" -eq 1 ] || fail "'$*' printed more than one line: $msg"
}
expect_rejected "--bogus" --bogus
expect_rejected "--scheme" --scheme nosuch
expect_rejected "-n" -n 0
expect_rejected "-n" -n abc
expect_rejected "nosuchcase" --init nosuchcase
expect_rejected "--kernel-exponent" --kernel-exponent 20
expect_rejected "--ngmax" --ngmax 50
expect_rejected "--courant" --courant 0
expect_rejected "--t-end" --t-end -1
expect_rejected "--threads" --threads 0
expect_rejected "-w" -n 10 -w inf                      # issue 21 fuzz finding: inf into an int
expect_rejected "-w" -n 10 -w 99999999999999999999999
if "$exe" --version | grep -q "HDF5 off"; then
    # A build without HDF5 (issue 18) refuses the options that need files, naming them.
    expect_rejected "-w: this build has no HDF5" -n 10 -s 1 -w 1
    expect_rejected "--restart" -n 10 --restart "$0"
else
    expect_rejected "--av-limiter" -n 10 -s 1 -w 1 -f rho,strain_xx
    # Optional fields exist only in runs that carry them (alpha: --av-switch, phi: gravity).
    expect_rejected "--av-switch" -n 10 -s 1 -w 1 -f rho,alpha
    expect_rejected "self-gravity" --init sedov -n 10 -s 1 -w 1 -f phi
fi
expect_rejected "carries no field" --init sedov -n 10 -s 2 --inject-fault 1:alpha:3:40
expect_rejected "smoothing length" -n 4 -s 1
expect_rejected "--theta" --init evrard --theta 1.5
expect_rejected "some axes only" --init square-patch --lattice -n 10 --G 1 -s 1
expect_rejected "--curve" --curve peano
expect_rejected "--energy-weights" --init sedov -n 10 -s 1 --scheme std --energy-weights
expect_rejected "ideal-gas" --init square-patch -n 10 -s 1 --scheme pe
expect_rejected "--on-sdc" --on-sdc maybe
expect_rejected "--backend" --backend tpu
# Issue 18, acceptance 3: where auto falls back to the CPU (no device, or a build without CUDA),
# --backend cuda is one line and exit 2, never a CUDA error dump.
backend=$("$exe" -n 8 -s 0 --out "$work/backend" 2>&1 | grep '^backend:')
echo "$backend" | grep -qE '^backend: (cpu \(OpenMP; auto: .+\)|cuda, .+ \(auto\))$' ||
    fail "the header's backend line: $backend"
if echo "$backend" | grep -q '^backend: cpu'; then
    expect_rejected "--backend cuda" --backend cuda -n 8 -s 1
fi

# Closed choices take their names in any case; the header shows every physics parameter and
# the run-control parameters that differ from their defaults (issue 15).
out=$("$exe" -n 10 -s 1 --curve Morton --on-sdc ABORT --out "$work/names" 2>&1)
echo "$out" | grep -q "curve morton" || fail "header lacks 'curve morton': $out"
echo "$out" | grep -q "on_sdc abort" || fail "header lacks 'on_sdc abort': $out"
"$exe" --help | grep -q "sound_speed (3500)" || fail "--help lacks the case parameters"

# A rollback directory that cannot be created (below a file): output I/O failure, exit code 3,
# one line naming the rollback point.
msg=$("$exe" --init sedov -n 10 -s 2 --sdc-rollback-dir "$work/run/diagnostics.csv/sub" \
    --out "$work/rb" 2>&1 >/dev/null)
rc=$?
[ $rc -eq 3 ] || fail "unwritable --sdc-rollback-dir exited $rc, expected 3: $msg"
echo "$msg" | grep -q "rollback point" || fail "unwritable --sdc-rollback-dir: $msg"
[ "$(echo "$msg" | wc -l)" -eq 1 ] || fail "unwritable --sdc-rollback-dir: more than one line: $msg"

# Parameter files (issue 22): every run writes DIR/run.toml with its resolved parameters;
# --config reads it back (the same run, to the last digit), the command line overrides the
# file, and a bad key, type or value is one line naming the file's line and the key.
snapshots=(-w 0.0002) # a custom value (time or count) in the file too, where snapshots exist
"$exe" --version | grep -q "HDF5 off" && snapshots=()
"$exe" --init sedov -n 10 -s 4 "${snapshots[@]}" --ng0 90 --out "$work/toml1" >/dev/null 2>&1
grep -q '^ng0 = 90 ' "$work/toml1/run.toml" || fail "run.toml lacks ng0 = 90"
grep -q '^# The parameters of this run, written by exasph ' "$work/toml1/run.toml" ||
    fail "run.toml does not name the version"
"$exe" --config "$work/toml1/run.toml" --out "$work/toml2" >/dev/null 2>&1 ||
    fail "--config run.toml failed"
cmp -s <(cut -d, -f1-19 "$work/toml1/diagnostics.csv") <(cut -d, -f1-19 "$work/toml2/diagnostics.csv") ||
    fail "--config run.toml did not repeat the run"
if [ ${#snapshots[@]} -gt 0 ]; then
    ls "$work/toml2"/snapshot_000004.h5 >/dev/null 2>&1 || fail "--config: no snapshots (-w)"
fi
h=$("$exe" --config "$work/toml1/run.toml" --ng0 110 -s 0 --out "$work/toml3" 2>&1 | grep '^physics:')
echo "$h" | grep -q "ng0 110" || fail "the command line should override the file: $h"
bad_file() { # NAME LINE_AND_KEY TOML_TEXT
    printf '%b' "$3" >"$work/$1.toml"
    expect_rejected "$work/$1.toml:$2" --config "$work/$1.toml"
}
bad_file unknown "3: unknown key 'bogus'" 'init = "sedov"\nside = 8\nbogus = 3\n'
bad_file wrong_type "2: 'side' takes an integer" 'init = "sedov"\nside = "eight"\n'
bad_file float_for_int "1: 'side' takes an integer" 'side = 8.5\n'
bad_file bool_for_number "1: 'courant' takes a number" 'courant = true\n'
bad_file string_for_flag "1: 'lattice' takes true or false" 'lattice = "yes"\n'
bad_file numbers_for_list "1: 'fields' takes a list of strings" 'fields = [1, 2]\n'
bad_file out_of_range "3: 'ng0': --ng0" 'init = "sedov"\n\nng0 = 5\n'
bad_file negative_steps "1: 'steps': --steps" 'steps = -3\n'
bad_file bad_choice "1: 'scheme'" 'scheme = "nosuch"\n'
bad_file table "1: unknown key 'physics'" '[physics]\nng0 = 50\n'
bad_file duplicate "3: .*'side'" 'init = "sedov"\nside = 8\nside = 9\n'
bad_file not_toml "1: " 'init = "sedov\n'

# Every example's parameter file is accepted (examples/: run with examples/run.sh CASE).
examples=$(cd "$(dirname "$0")/../../examples" && pwd)
"$exe" --version | grep -q "HDF5 off" && examples=/nonexistent # they write snapshots
for params in "$examples"/*/params.toml; do
    [ -f "$params" ] || continue
    name=$(basename "$(dirname "$params")")
    h=$("$exe" --config "$params" --lattice -s 0 --out "$work/example" 2>&1)
    echo "$h" | grep -q "^case $name," || fail "examples/$name/params.toml: $h"
done

"$exe" --help | grep -q -- "--kernel-exponent" || fail "--help lacks options"
"$exe" --version | grep -q "exasph" || fail "--version"

if [ $failures -eq 0 ]; then echo "cli: all checks passed"; else exit 1; fi
