#!/usr/bin/env python3
"""Re-runs every hostile case of issue 15 against a built gale and prints one table row per case
with PASS or FAIL decided by the case's own check (docs/reliability.md, "Hostile cases").

    tests/reliability/hostile/run.sh [BUILD_DIR] [--group NAME ...] [--keep] [--markdown FILE]

Each case gets an empty working folder under a scratch folder (removed at the end unless --keep).
Exit 0 when every case passes, 1 otherwise.
"""

import argparse
import os
import shutil
import sys

from gale_run import Gale, scratch_folder
import cases_disk_paths
import cases_signals
import cases_checks

GROUPS = {
    "disk": cases_disk_paths.full_disk,
    "paths": cases_disk_paths.careless_paths,
    "signals": cases_signals.signals,
    "stale": cases_signals.stale_temporaries,
    "concurrent": cases_signals.concurrent_renders,
    "memory": cases_checks.memory,
    "input": cases_checks.bounded_input,
    "silent": cases_checks.silent_wrong_output,
    "float": cases_checks.float_range,
    "work": cases_checks.unbounded_work,
}


class Table:
    """Rows of (group, case, expected, observed, PASS/FAIL), printed as they come."""

    def __init__(self):
        self.rows = []

    def add(self, group, case, expected, ok, observed):
        row = (group, case, expected, "PASS" if ok else "FAIL", observed)
        self.rows.append(row)
        print("%-4s  %-10s  %s\n      expected: %s\n      observed: %s" %
              (row[3], group, case, expected, observed.replace("\n", " | ")[:400]), flush=True)

    def check(self, group, case, expected, fn):
        """Runs fn() -> (ok, observed); an exception is a FAIL naming it."""
        try:
            ok, observed = fn()
        except Exception as e:  # a case that breaks is a failed case, not a broken runner
            ok, observed = False, "%s: %s" % (type(e).__name__, e)
        self.add(group, case, expected, ok, observed)

    def write_markdown(self, path):
        with open(path, "w") as f:
            f.write("| group | case | expected | result | observed |\n| --- | --- | --- | --- | --- |\n")
            for row in self.rows:
                cells = [c.replace("|", "\\|").replace("\n", " ") for c in row]
                f.write("| %s | %s | %s | %s | %s |\n" % (cells[0], cells[1], cells[2], cells[3],
                                                         cells[4]))

    def summary(self):
        failed = [r for r in self.rows if r[3] == "FAIL"]
        print("\n%d cases, %d passed, %d failed" % (len(self.rows), len(self.rows) - len(failed),
                                                   len(failed)))
        for r in failed:
            print("FAIL  %-10s  %s" % (r[0], r[1]))
        return not failed


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    repo = os.path.normpath(os.path.join(here, "..", "..", ".."))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("build", nargs="?", default=os.path.join(repo, "build"),
                    help="build folder holding app/gale and tests/libgale_full_disk_shim.so")
    ap.add_argument("--group", action="append", choices=sorted(GROUPS),
                    help="run only these groups (repeatable)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder")
    ap.add_argument("--markdown", metavar="FILE", help="also write the table as Markdown to FILE")
    args = ap.parse_args()
    gale_exe = os.path.join(args.build, "app", "gale")
    shim = os.path.join(args.build, "tests", "libgale_full_disk_shim.so")
    for path in (gale_exe, shim):
        if not os.path.exists(path):
            sys.exit("run.py: %s does not exist; build the targets gale and gale_full_disk_shim"
                     % path)
    scratch = scratch_folder()
    gale = Gale(gale_exe, shim, scratch)
    table = Table()
    ctx = {"gale": gale, "repo": repo, "table": table}
    try:
        for name in args.group or GROUPS:
            print("== %s" % name, flush=True)
            GROUPS[name](ctx)
    finally:
        if args.keep:
            print("scratch folder kept: %s" % scratch)
        else:
            shutil.rmtree(scratch, ignore_errors=True)
    if args.markdown:
        table.write_markdown(args.markdown)
    sys.exit(0 if table.summary() else 1)


if __name__ == "__main__":
    main()
