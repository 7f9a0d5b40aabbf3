#!/usr/bin/python3
"""Per-step timings of one benchmark run, steps 2.. (bench/compare.sh).

step_timings.py exasph RUN_DIR   reads RUN_DIR/out/diagnostics.csv (exasph's per-step phase
                                 timers of rank 0)
step_timings.py ref RUN_DIR      reads RUN_DIR/log (the reference's "# Phase: Xs" lines and
                                 "=== Total time for iteration(k) Xs")
Prints "seconds_per_step density_seconds momentum_energy_seconds particles", the means over
steps 2.. (step 1 carries start-up work in both codes).
"""
import csv
import re
import sys

# The reference's density work: its std propagator's Density, its ve propagator's XMass and
# Normalization & Gradh; its momentum-energy pass under either name.
REF_DENSITY = {"Density", "XMass", "Normalization & Gradh"}
REF_MOMENTUM = {"MomentumEnergyIAD", "MomentumAndEnergy"}


def exasph(run_dir):
    with open(f"{run_dir}/out/diagnostics.csv") as f:
        rows = [r for r in csv.DictReader(f) if int(r["step"]) >= 2]
    if not rows:
        sys.exit(f"{run_dir}: no step after the first in diagnostics.csv")
    step = [sum(float(v) for k, v in r.items() if k.startswith("t_")) for r in rows]
    dens = [float(r["t_density"]) for r in rows]
    mom = [float(r["t_momentum_energy"]) for r in rows]
    return step, dens, mom, int(rows[-1]["n"])


def reference(run_dir):
    step, dens, mom = [], [], []
    d = m = 0.0
    n = 0
    with open(f"{run_dir}/log") as f:
        for line in f:
            if g := re.match(r"Data generated for (\d+) global particles", line):
                n = int(g.group(1))
            elif g := re.match(r"# (.+): ([0-9.eE+-]+)s$", line.strip()):
                name, t = g.group(1), float(g.group(2))
                d += t if name in REF_DENSITY else 0
                m += t if name in REF_MOMENTUM else 0
            elif g := re.match(r"=== Total time for iteration\((\d+)\) ([0-9.eE+-]+)s", line):
                if int(g.group(1)) >= 2:
                    step.append(float(g.group(2)))
                    dens.append(d)
                    mom.append(m)
                d = m = 0.0
    if not step or not n:
        sys.exit(f"{run_dir}/log: no timed iteration after the first, or no particle count")
    return step, dens, mom, n


def main():
    code, run_dir = sys.argv[1], sys.argv[2]
    step, dens, mom, n = {"exasph": exasph, "ref": reference}[code](run_dir)
    mean = lambda v: sum(v) / len(v)
    print(f"{mean(step):.4g} {mean(dens):.4g} {mean(mom):.4g} {n}")


if __name__ == "__main__":
    main()
