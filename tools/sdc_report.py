#!/usr/bin/env python3
"""Markdown tables from a fault-injection sweep (CSV written by the CTest test_sdc with
EXASPH_SDC_CSV=FILE): per field and per bit class, injections, harmful flips, detections.

    /usr/bin/python3 tools/sdc_report.py sweep.csv
"""
import csv
import sys
from collections import defaultdict


def bit_class(bit):
    if bit == 63:
        return "sign (63)"
    if bit >= 52:
        return "exponent (52-62)"
    if bit >= 40:
        return "mantissa high (40-51)"
    if bit >= 20:
        return "mantissa mid (20-39)"
    return "mantissa low (0-19)"


def table(rows, key, title):
    groups = defaultdict(list)
    for r in rows:
        groups[key(r)].append(r)
    print(f"| {title} | injections | harmful | harmful detected | detected (all) | "
          f"also by an invariant | rollback = clean |")
    print("|---|---|---|---|---|---|---|")
    for k in sorted(groups):
        g = groups[k]
        harm = [r for r in g if r["harmful"] == "1"]
        print(f"| {k} | {len(g)} | {len(harm)} | "
              f"{sum(r['detected'] == '1' for r in harm)} | "
              f"{sum(r['detected'] == '1' for r in g)} | "
              f"{sum('invariant' in r['mechanism'] for r in g)} | "
              f"{sum(r['rollback_equal'] == '1' for r in g)} |")
    print()


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    try:
        with open(sys.argv[1], newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as exc:
        print(f"sdc_report.py: {exc}", file=sys.stderr)
        return 2
    if not rows or "mechanism" not in rows[0]:
        print(f"sdc_report.py: {sys.argv[1]}: not a sweep CSV", file=sys.stderr)
        return 2
    table(rows, lambda r: r["field"], "field")
    table(rows, lambda r: bit_class(int(r["bit"])), "bit")
    harmless_invariant = sum(r["harmful"] == "0" and "invariant" in r["mechanism"] for r in rows)
    print(f"{len(rows)} injections; harmless flips also caught by an invariant: "
          f"{harmless_invariant}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
