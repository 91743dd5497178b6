#!/usr/bin/env python3
"""Elasticity benchmark without contact (not a test): for a linear elastic
block, print DoFs, assembly time, linear solver time (factorization or AMG
set-up plus solve) and peak memory, for 2D at about 1e5 and 1e6 DoFs and 3D
at about 1e5 and 5e5 DoFs, each with the direct solver (MUMPS) and with
GMRES + ML AMG. Every number comes from the run's own timings.csv.

Usage: python3 study/benchmark.py --glide build/glide [--quick] [--markdown FILE]

A failed run (or a missing binary) stops the benchmark with exit status 2;
no row is printed for it and the --markdown file is not written.
"""
import argparse
import csv
import os
import platform
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import study_runs  # noqa: E402

# (label, dimension, subdivisions per side, global refinements)
CASES = [
    ("2D 1e5", 2, 28, 3),
    ("2D 1e6", 2, 44, 4),
    ("3D 1e5", 3, 8, 2),
    ("3D 5e5", 3, 7, 3),
]


def run(glide, dim, n, refinements, solver, out):
    scene = os.path.join(HERE, f"benchmark-{dim}d.prm")
    name = f"bench-{dim}d-{n}-{refinements}-{solver}"
    cmd = [glide, scene, "--set", f"Output/Directory={out}", "--set", f"Scene name={name}",
           "--set", "Body body/Block/Subdivisions=" + ", ".join([str(n)] * dim),
           "--set", f"Body body/Refinement/Global refinements={refinements}",
           "--set", f"Linear solver/Type={solver}"]
    p = study_runs.run(cmd)
    if p.returncode != 0:  # no contact: even a failed load step is a failure here
        print(p.stdout[-3000:], p.stderr[-3000:])
        raise study_runs.StudyError(f"{study_runs.command_text(cmd)} failed ({study_runs.describe(p)})")
    if not os.path.exists(os.path.join(out, name, "timings.csv")):
        raise study_runs.StudyError(f"{study_runs.command_text(cmd)} exited 0 without writing timings.csv")
    with open(os.path.join(out, name, "timings.csv")) as f:
        t = {r["quantity"]: r["value"] for r in csv.DictReader(f)}
    g = lambda k: float(t.get(k, 0.0))
    return {
        "dofs": int(t["dofs"]),
        "assembly": g("time:assembly: Jacobian") + g("time:assembly: residual"),
        "solver": g("time:linear solver: setup") + g("time:linear solver: solve"),
        "setup": g("time:linear solver: setup"),
        "total": g("total_wall_time"),
        "memory": g("peak_memory_mib"),
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--glide", required=True)
    ap.add_argument("--quick", action="store_true", help="only the two smaller sizes")
    ap.add_argument("--markdown", help="also write the table to this file")
    a = ap.parse_args()
    study_runs.main(benchmark, a, os.path.abspath(a.glide))


def benchmark(a):
    out = tempfile.mkdtemp(prefix="glide-bench-")
    lines = ["| case | solver | DoFs | assembly [s] | linear solver [s] (of which set-up) | total [s] | peak memory [MiB] |",
             "|---|---|---:|---:|---:|---:|---:|"]
    print("\n".join(lines), flush=True)
    for label, dim, n, r in CASES:
        if a.quick and "1e5" not in label:
            continue
        for solver in ("direct", "amg"):
            res = run(os.path.abspath(a.glide), dim, n, r, solver, out)
            line = (f"| {label} | {'MUMPS' if solver == 'direct' else 'GMRES+AMG'} | {res['dofs']} | "
                    f"{res['assembly']:.2f} | {res['solver']:.2f} ({res['setup']:.2f}) | {res['total']:.2f} | "
                    f"{res['memory']:.0f} |")
            print(line, flush=True)
            lines.append(line)
    machine = f"{platform.machine()}, {os.cpu_count()} cores, Python {platform.python_version()}"
    print(f"\nmachine: {machine}")
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
