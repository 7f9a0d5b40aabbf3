#!/usr/bin/env bash
# Runs one example and plots it:  bash examples/run.sh CASE [exasph options...]
#   CASE: a folder of examples/ (its params.toml); options override the file (e.g. -n 30).
#   MPIRUN="mpirun -np 4" runs it on 4 ranks; EXASPH=path picks the binary (build/exasph).
# Output in CASE-output/ (the file's `out`) in the current directory, the figure beside it.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(dirname "$here")
case_name=${1:?usage: examples/run.sh CASE [exasph options...]}
shift
params=$here/$case_name/params.toml
[ -f "$params" ] || { echo "examples/run.sh: no example '$case_name'" >&2; exit 2; }
exe=${EXASPH:-$root/build/exasph}
[ -x "$exe" ] || bash "$root/scripts/setup.sh"
read -r -a mpirun <<< "${MPIRUN:-}"
out=$case_name-output
"${mpirun[@]}" "$exe" --config "$params" --out "$out" "$@"
py=/usr/bin/python3
last=$(ls "$out"/snapshot_*.h5 | tail -1)
case $case_name in
sedov | noh) $py "$root/tools/profiles.py" "$last" -o "$out.png" --exasph "$exe" ;;
evrard) $py "$root/tools/evrard.py" "$out" -o "$out" ;;
square-patch) $py "$root/tools/case_plots.py" square "$out"/snapshot_*.h5 -o "$out.png" ;;
gresho-chan) $py "$root/tools/case_plots.py" gresho "$out"/snapshot_*.h5 -o "$out.png" ;;
isobaric-cube) $py "$root/tools/case_plots.py" slice "$last" -o "$out.png" ;;
kelvin-helmholtz) $py "$root/tools/case_plots.py" kh "$out"/snapshot_*.h5 -o "$out.png" ;;
wind-cloud) $py "$root/tools/case_plots.py" wind "$out"/snapshot_*.h5 -o "$out.png" ;;
turbulence) $py "$root/tools/case_plots.py" turb "$out"/snapshot_*.h5 -o "$out.png" ;;
*) echo "examples/run.sh: no plot for $case_name" ;;
esac
echo "run in $out/ (parameters as run: $out/run.toml; ParaView: $out/snapshots.xdmf)"
