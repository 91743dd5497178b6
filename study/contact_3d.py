#!/usr/bin/env python3
"""3D contact cost study (issue 14; a benchmark, not a test): the Hertz
quarter model of parameters/hertz-3d-elastic.prm (elastic sphere R = 1 pressed
0.02 into an elastic block, E = 1, nu = 0.3) with a uniform block of N x N x N
cells over [0, 1] x [-1, 0] x [0, 1] (no hanging nodes on the slave, the
block's top), in 2 load steps, for several N, with
  - mortar, hard contact, GMRES + ML AMG on the condensed system, and
  - node to surface (the default), hard contact, the direct solver (MUMPS),
and, where asked, other pairs. Per run: DoFs, Newton iterations, total time,
time per Newton iteration, the contact share (contact residual and Jacobian
evaluations) and the linear solver share of the run, peak memory, and the
peak nodal pressure against Hertz's p0. Every number comes from the run's own
statistics.csv, timings.csv and contact CSV.

With --processes 1,2 each run is repeated under `mpirun -np P` (issue 15,
doc/performance.md "Contact in parallel"): the table then gives the peak
memory of the largest process and the speed-up against one process.

With --ceiling (and --processes 1,P) P one-process runs are also started at
once: P times one run's time alone over their mean time is the speed-up the
machine allows on independent work (cores that share memory bandwidth and
cache do not give P times the throughput of one), the ceiling of any
P-process run.

With --scenes-2d the shipped 2D Hertz scenes run instead (whole runs with
VTU output), for the small-problem overhead of parallel runs.

Usage: python3 study/contact_3d.py --glide build/glide [--sizes 21,32]
       [--runs mortar-amg,nts-direct] [--processes 1] [--ceiling]
       [--markdown FILE]
       python3 study/contact_3d.py --glide build/glide --scenes-2d --processes 1,2
"""
import argparse
from concurrent.futures import ThreadPoolExecutor
import csv
import math
import os
import platform
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import study_runs  # noqa: E402
SCENE = os.path.join(HERE, "..", "parameters", "hertz-3d-elastic.prm")

RUNS = {
    "mortar-amg": ("mortar", "GMRES+AMG (condensed)", ["Contact pair hertz/Formulation=mortar",
                                                       "Linear solver/Type=amg"]),
    "mortar-direct": ("mortar", "MUMPS", ["Contact pair hertz/Formulation=mortar",
                                          "Linear solver/Type=direct"]),
    "nts-direct": ("node to surface", "MUMPS", ["Linear solver/Type=direct"]),
    "nts-amg": ("node to surface", "GMRES+AMG (condensed)", ["Linear solver/Type=amg"]),
}


def sphere_refinement(n):
    """The sphere's finest cells about as fine as the block's (h = 1 / n)
    over the contact zone (a = 0.146): local refinement levels and the
    radius of the finest ones."""
    levels = max(3, round(math.log2(n / 4)))
    return [f"Body sphere/Refinement/Local refinements={levels}",
            "Body sphere/Refinement/Minimum refinement radius=0.25"]


def command(glide, n, key, out, processes=1, tag=""):
    """The command of one run and its scene name."""
    formulation, solver, sets = RUNS[key]
    name = f"contact3d-{n}-{key}-np{processes}{tag}"
    mpi = ["mpirun", "-np", str(processes)] if processes > 1 else []
    cmd = mpi + [glide, SCENE, "--set", f"Output/Directory={out}", "--set", f"Scene name={name}",
           "--set", "Output/Write VTU=false", "--set", "Load stepping/Number of steps=2",
           "--set", "Body block/Block/Lower corner=0, -1, 0", "--set", "Body block/Block/Upper corner=1, 0, 1",
           "--set", f"Body block/Block/Subdivisions={n}, {n}, {n}",
           "--set", "Body block/Refinement/Local refinements=0"]
    for s in sphere_refinement(n) + sets:
        cmd += ["--set", s]
    return cmd, name


def run(glide, n, key, out, processes=1):
    """The run's result, or glide's reason (a string) if a load step
    failed; any other failure raises study_runs.StudyError."""
    cmd, name = command(glide, n, key, out, processes)
    p = study_runs.run(cmd)
    reason = study_runs.outcome(p, study_runs.command_text(cmd))
    if reason is not None:
        print(p.stdout[-3000:], p.stderr[-3000:])
        return reason
    return result(n, key, out, name)


def concurrent(glide, n, key, out, copies):
    """@p copies one-process runs at the same time (the machine's
    throughput with every core busy on independent work); their results,
    or glide's reason if a load step of one failed."""
    commands = [command(glide, n, key, out, 1, f"-copy{c}") for c in range(copies)]
    with ThreadPoolExecutor(max_workers=copies) as pool:
        try:
            done = list(pool.map(lambda c: study_runs.run(c[0]), commands))
        except BaseException:
            study_runs.stop_all()
            raise
    results = []
    for p, (cmd, name) in zip(done, commands):
        reason = study_runs.outcome(p, study_runs.command_text(cmd))
        if reason is not None:
            print(p.stderr[-3000:])
            return reason
        results.append(result(n, key, out, name))
    return results


def result(n, key, out, name):
    formulation, solver, _ = RUNS[key]
    d = os.path.join(out, name)
    for f in ("timings.csv", "statistics.csv"):
        if not os.path.exists(os.path.join(d, f)):
            raise study_runs.StudyError(f"the run {name} exited 0 without writing {os.path.join(d, f)}")
    with open(os.path.join(d, "timings.csv")) as f:
        t = {r["quantity"]: r["value"] for r in csv.DictReader(f)}
    with open(os.path.join(d, "statistics.csv")) as f:
        rows = list(csv.DictReader(f))
    g = lambda k: float(t.get(k, 0.0))
    last = sorted(x for x in os.listdir(d) if x.startswith("contact-hertz-") and x.endswith(".csv"))[-1]
    with open(os.path.join(d, last)) as f:
        peak = max(float(r["CPRESS"]) for r in csv.DictReader(f))
    F = -4 * float(rows[-1]["contact_hertz_force_y"])
    e_star = 1 / (2 * (1 - 0.3 ** 2))
    a = (3 * F / (4 * e_star)) ** (1 / 3)
    p0 = 3 * F / (2 * math.pi * a * a)
    newton = sum(int(float(r["kinsol_iterations"])) for r in rows)
    total = g("total_wall_time")
    contact = g("time:contact: residual") + g("time:contact: Jacobian")
    solver_time = g("time:linear solver: setup") + g("time:linear solver: solve")
    return {"n": n, "formulation": formulation, "solver": solver, "dofs": int(t["dofs"]),
            "newton": newton, "per_step": [int(float(r["kinsol_iterations"])) for r in rows],
            "cut_backs": int(float(rows[-1].get("cut_backs", 0))),
            "gmres": sum(int(float(r["linear_iterations"])) for r in rows),
            "total": total, "per_iteration": total / max(newton, 1),
            # The Newton iterations alone (without mesh, set-up and output,
            # which a run pays once): assembly, contact, linear solver.
            "loop_per_iteration": (g("time:assembly: residual") + g("time:assembly: Jacobian") + contact
                                   + solver_time) / max(newton, 1),
            "contact_share": contact / total, "solver_share": solver_time / total,
            "memory": g("peak_memory_mib"), "per_process": g("peak_memory_per_process_mib"),
            "p0_error": peak / p0 - 1}


def finish(a, lines, note):
    """Print the note under the table; append both to --markdown's file."""
    print(note)
    if a.markdown:
        with open(a.markdown, "a") as f:
            f.write("\n".join(lines) + "\n" + note)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--glide", required=True)
    ap.add_argument("--sizes", default="21,32")
    ap.add_argument("--runs", default="mortar-amg,nts-direct")
    ap.add_argument("--processes", default="1", help="comma-separated numbers of MPI processes")
    ap.add_argument("--markdown", help="append the table to this file")
    ap.add_argument("--scenes-2d", action="store_true",
                    help="instead: the shipped 2D Hertz scenes (parameters/hertz-2d.prm, hertz-2d-elastic.prm) "
                         "on the given numbers of processes")
    ap.add_argument("--ceiling", action="store_true",
                    help="with --processes 1,P: also P one-process runs at once (the machine's own limit "
                         "on the speed-up)")
    a = ap.parse_args()
    return study_runs.main(tables, a, a.glide)


def tables(a):
    processes = [int(x) for x in a.processes.split(",")]
    if a.scenes_2d:
        return table_2d(a, processes)
    if processes != [1]:
        return parallel_table(a, processes)
    out = tempfile.mkdtemp(prefix="glide-contact3d-")
    header = ("| N | formulation | linear solver | DoFs | Newton its (per step) | cut-backs | GMRES its | "
              "total [s] | per Newton it. [s] | contact share | linear solver share | peak memory [MiB] | "
              "MiB per 1e3 DoFs | peak p / p0 - 1 |")
    lines = [header, "|---:|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    print(lines[0], flush=True)
    for n in [int(x) for x in a.sizes.split(",")]:
        for key in a.runs.split(","):
            r = run(a.glide, n, key, out)
            if isinstance(r, str):
                line = f"| {n} | {RUNS[key][0]} | {RUNS[key][1]} | did not converge: {r} | | | | | | | | | | |"
            else:
                line = (f"| {n} | {r['formulation']} | {r['solver']} | {r['dofs']} | {r['newton']} "
                        f"({', '.join(map(str, r['per_step']))}) | {r['cut_backs']} | {r['gmres']} | "
                        f"{r['total']:.1f} | {r['per_iteration']:.2f} | {100 * r['contact_share']:.0f} % | "
                        f"{100 * r['solver_share']:.0f} % | {r['memory']:.0f} | "
                        f"{1000 * r['memory'] / r['dofs']:.1f} | {100 * r['p0_error']:+.2f} % |")
            lines.append(line)
            print(line, flush=True)
    note = (f"\nMeasured with `python3 study/contact_3d.py --sizes {a.sizes} --runs {a.runs}` on "
            f"{platform.machine()}, {os.cpu_count()} cores, one process.\n")
    finish(a, lines, note)


def parallel_table(a, processes):
    """Each run on 1, 2, ... processes: time per Newton iteration (the whole
    run, and the Newton iterations alone), contact share, peak memory of the
    largest process, speed-up and parallel efficiency against the first
    number of processes. With --ceiling, also as many one-process runs at
    once as the largest number of processes: the speed-up the machine
    itself allows (its throughput with every core busy, against one run
    alone), which no parallel run can exceed."""
    out = tempfile.mkdtemp(prefix="glide-contact3d-mpi-")
    lines = ["| N | formulation | linear solver | DoFs | processes | Newton its | per Newton it. [s] | "
             "Newton loop per it. [s] | contact share | linear solver share | "
             "peak memory, largest process [MiB] | speed-up | speed-up, Newton loop | efficiency | "
             "memory per process / 1 process |",
             "|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    print(lines[0], flush=True)
    for n in [int(x) for x in a.sizes.split(",")]:
        for key in a.runs.split(","):
            first = None
            for np_ in processes:
                r = run(a.glide, n, key, out, np_)
                if isinstance(r, str):
                    line = f"| {n} | {RUNS[key][0]} | {RUNS[key][1]} | | {np_} | did not converge: {r} | | | | | | | | | |"
                else:
                    first = first or (np_, r)
                    speed = first[1]["per_iteration"] / r["per_iteration"]
                    loop = first[1]["loop_per_iteration"] / r["loop_per_iteration"]
                    line = (f"| {n} | {r['formulation']} | {r['solver']} | {r['dofs']} | {np_} | {r['newton']} | "
                            f"{r['per_iteration']:.2f} | {r['loop_per_iteration']:.2f} | "
                            f"{100 * r['contact_share']:.0f} % | "
                            f"{100 * r['solver_share']:.0f} % | {r['per_process']:.0f} | {speed:.2f} | "
                            f"{loop:.2f} | {100 * speed * first[0] / np_:.0f} % | "
                            f"{r['per_process'] / first[1]['per_process']:.2f} |")
                lines.append(line)
                print(line, flush=True)
            copies = max(processes)
            if a.ceiling and first is not None and first[0] == 1 and copies > 1:
                rs = concurrent(a.glide, n, key, out, copies)
                if isinstance(rs, str):
                    line = (f"| {n} | {RUNS[key][0]} | {RUNS[key][1]} | | {copies} x 1 at once | did not converge: "
                            f"{rs} | | | | | | | | | |")
                else:
                    per = sum(x["per_iteration"] for x in rs) / copies
                    loop = sum(x["loop_per_iteration"] for x in rs) / copies
                    line = (f"| {n} | {RUNS[key][0]} | {RUNS[key][1]} | {rs[0]['dofs']} | "
                            f"{copies} runs of 1 at once | {rs[0]['newton']} | {per:.2f} | {loop:.2f} | | | | "
                            f"ceiling {copies * first[1]['per_iteration'] / per:.2f} | "
                            f"ceiling {copies * first[1]['loop_per_iteration'] / loop:.2f} | | |")
                lines.append(line)
                print(line, flush=True)
    note = (f"\nMeasured with `python3 study/contact_3d.py --sizes {a.sizes} --runs {a.runs} "
            f"--processes {a.processes}{' --ceiling' if a.ceiling else ''}` on {platform.machine()}, "
            f"{os.cpu_count()} cores.\n")
    finish(a, lines, note)


SCENES_2D = ["hertz-2d.prm", "hertz-2d-elastic.prm"]


def table_2d(a, processes):
    """The shipped 2D Hertz scenes (rigid flat; two elastic bodies), whole
    runs with VTU output, on 1, 2, ... processes: the small-problem
    overhead of running in parallel."""
    out = tempfile.mkdtemp(prefix="glide-contact2d-mpi-")
    lines = ["| scene | DoFs | processes | Newton its | total [s] | per Newton it. [s] | contact share | "
             "linear solver share | output share | peak memory, largest process [MiB] | speed-up |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    print(lines[0], flush=True)
    for scene in SCENES_2D:
        first = None
        for np_ in processes:
            name = f"{os.path.splitext(scene)[0]}-np{np_}"
            mpi = ["mpirun", "-np", str(np_)] if np_ > 1 else []
            cmd = mpi + [a.glide, os.path.join(HERE, "..", "parameters", scene), "--set",
                         f"Output/Directory={out}", "--set", f"Scene name={name}"]
            p = study_runs.run(cmd)
            reason = study_runs.outcome(p, study_runs.command_text(cmd))
            if reason is not None:
                print(p.stdout[-3000:], p.stderr[-3000:])
                lines.append(f"| {scene} | | {np_} | did not converge: {reason} | | | | | | | |")
                print(lines[-1], flush=True)
                continue
            d = os.path.join(out, name)
            for f in ("timings.csv", "statistics.csv"):
                if not os.path.exists(os.path.join(d, f)):
                    raise study_runs.StudyError(f"{study_runs.command_text(cmd)} exited 0 without writing {f}")
            with open(os.path.join(d, "timings.csv")) as f:
                t = {r["quantity"]: r["value"] for r in csv.DictReader(f)}
            with open(os.path.join(d, "statistics.csv")) as f:
                rows = list(csv.DictReader(f))
            g = lambda k: float(t.get(k, 0.0))
            newton = sum(int(float(r["kinsol_iterations"])) for r in rows)
            total = g("total_wall_time")
            first = first or total
            line = (f"| {os.path.splitext(scene)[0]} | {int(t['dofs'])} | {np_} | {newton} | {total:.2f} | "
                    f"{total / max(newton, 1):.3f} | "
                    f"{100 * (g('time:contact: residual') + g('time:contact: Jacobian')) / total:.1f} % | "
                    f"{100 * (g('time:linear solver: setup') + g('time:linear solver: solve')) / total:.0f} % | "
                    f"{100 * g('time:output') / total:.0f} % | {g('peak_memory_per_process_mib'):.0f} | "
                    f"{first / total:.2f} |")
            lines.append(line)
            print(line, flush=True)
    note = (f"\nMeasured with `python3 study/contact_3d.py --scenes-2d --processes {a.processes}` on "
            f"{platform.machine()}, {os.cpu_count()} cores.\n")
    finish(a, lines, note)


if __name__ == "__main__":
    main()
