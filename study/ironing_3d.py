#!/usr/bin/env python3
"""3D ironing study (issue 14; a study, not a test): the 3D ironing problem
of reference/benchmarks.md section 4 (after Puso and Laursen 2004). A soft
slab 9 x 4 x 3 (E = 1, nu = 0.3, fixed at its bottom) and a stiff die, a
cylindrical segment (half tube) of outer radius 3, thickness 0.2 and width
5.2 (E = 1000, nu = 0.499), 0.03 above the slab; the die is pressed down
1.4 (load factor 0 to 0.26) and slid 3.0 along x (0.26 to 1) by a prescribed
displacement of its flat ends. Geometrically nonlinear, frictionless, hard
contact. Half model: the plane z = 0 halves the slab's width 4 and the die's
width 5.2 (ZSYMM on both bodies).

As in the 2D study (study/scenes/ironing-2d.prm): the slab's top is the
slave, the die's outer surface the master, and the slide is 3.0, not the
reference's 4.0 (the die's edge would pass the slab's end).

The die is meshed here (an Abaqus file with C3D8 elements, written into the
output directory with the scene), the slab is a built-in block. Per run:
whether it reached the end, steps, cut-backs, Newton iterations per step
(mean / max), the mean normal force on the die over the steady sliding
(after 1.0 of the slide) and its ripple (max - min) / mean, the tangential
force's range over the mean normal force, time and peak memory.

Usage: python3 study/ironing_3d.py --glide build/glide [--runs mortar,nts]
       [--output DIR] [--markdown FILE] [--steps 100] [--slab 36,12,8]

Exit status 0: every run reached the end; 1: a load step of a run failed
(its row says how far it got, glide's reason is printed); 2: the study
failed (a missing binary, a run that failed otherwise or reached --limit):
no row is printed for that run and --markdown is not written.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import study_runs  # noqa: E402

# Peak memory of a run (its "Maximum resident set size").
TIME = "/usr/bin/time"

# Steady sliding: after 1.0 of the 3.0 slide (load factor 0.26 + 0.74 / 3).
STEADY = 0.26 + 0.74 / 3

RUNS = {
    "mortar": ("mortar", ["Contact pair ironing/Formulation=mortar"]),
    "nts": ("node to surface, f = 0.2", []),
}


def write_die(path, n_around, n_width, n_thick=1, center=(2.5, 6.03), r_in=2.8, r_out=3.0, width=2.6):
    """The lower half of a tube along z (axis through center, z from 0 to
    width), as C3D8 elements: element set DIE, surface OUTER (the outer
    faces), node sets ENDS (the two flat ends at the top) and SYM (z = 0)."""
    def node(i, j, k):
        return 1 + i + (n_around + 1) * (j + (n_thick + 1) * k)

    lines = ["*NODE"]
    for k in range(n_width + 1):
        for j in range(n_thick + 1):
            for i in range(n_around + 1):
                theta = math.pi + math.pi * i / n_around
                r = r_in + (r_out - r_in) * j / n_thick
                lines.append(f"{node(i, j, k)}, {center[0] + r * math.cos(theta):.15g}, "
                             f"{center[1] + r * math.sin(theta):.15g}, {width * k / n_width:.15g}")
    lines.append("*ELEMENT, TYPE=C3D8, ELSET=DIE")
    outer = []
    e = 0
    for k in range(n_width):
        for j in range(n_thick):
            for i in range(n_around):
                e += 1
                # Face 1-2-3-4 at z_k, counterclockwise seen from +z (i
                # runs along +x at the bottom, j along -y), 5-8 at z_k+1.
                bottom = [node(i, j, k), node(i, j + 1, k), node(i + 1, j + 1, k), node(i + 1, j, k)]
                top = [n + (n_around + 1) * (n_thick + 1) for n in bottom]
                lines.append(f"{e}, " + ", ".join(str(n) for n in bottom + top))
                if j == n_thick - 1:
                    outer.append(e)  # nodes 2, 3, 6, 7: Abaqus face S4 (2-6-7-3)
    lines.append("*NSET, NSET=ENDS")
    ends = [node(i, j, k) for k in range(n_width + 1) for j in range(n_thick + 1) for i in (0, n_around)]
    lines += [", ".join(str(n) for n in ends[a:a + 8]) for a in range(0, len(ends), 8)]
    lines.append("*NSET, NSET=SYM")
    sym = [node(i, j, 0) for j in range(n_thick + 1) for i in range(n_around + 1)]
    lines += [", ".join(str(n) for n in sym[a:a + 8]) for a in range(0, len(sym), 8)]
    lines.append("*SURFACE, NAME=OUTER, TYPE=ELEMENT")
    lines += [f"{e}, S4" for e in outer]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


SCENE = """# 3D ironing (study/ironing_3d.py; reference/benchmarks.md section 4).
set Dimension     = 3
set Analysis type = 3d
subsection Discretization
  set Geometric nonlinearity = true
end
set Bodies        = slab, die
set Boundary conditions = ground, slab_symmetry, die_symmetry, drive
set Contact pairs = ironing
subsection Body slab
  subsection Block
    set Lower corner = 0, 0, 0
    set Upper corner = 9, 3, 2
    set Subdivisions = {slab}
  end
  subsection Material
    set Young's modulus = 1
    set Poisson's ratio = 0.3
  end
end
subsection Body die
  set Mesh        = file
  set Mesh file   = die.inp
  set Element set = DIE
  subsection Material
    set Young's modulus = 1000
    set Poisson's ratio = 0.499
  end
end
subsection Boundary condition ground
  set Surface = slab.bottom
  set Type    = fixed
end
subsection Boundary condition slab_symmetry
  set Surface = slab.back
  set Type    = ZSYMM
end
subsection Boundary condition die_symmetry
  # A node set of the mesh file: a list of surfaces cannot hold it.
  set Surface = die.SYM
  set Type    = ZSYMM
end
subsection Boundary condition drive
  set Surface  = die.ENDS
  set Type     = displacement
  set Function = 3.0*max(0, (t - 0.26)/0.74); -1.4*min(1, t/0.26); 0
end
subsection Contact pair ironing
  set Slave  = slab.top
  set Master = die.OUTER
end
subsection Nonlinear solver
  set Strategy = line search
end
subsection Load stepping
  set Number of steps   = {steps}
  set Maximum cut-backs = 10
end
"""


def run(glide, out, key, slab, die, steps, limit):
    label, sets = RUNS[key]
    scene_dir = os.path.join(out, "scene")
    os.makedirs(scene_dir, exist_ok=True)
    write_die(os.path.join(scene_dir, "die.inp"), *die)
    scene = os.path.join(scene_dir, "ironing-3d.prm")
    with open(scene, "w") as f:
        f.write(SCENE.format(slab=", ".join(str(n) for n in slab), steps=steps))
    name = f"ironing3d-{key}"
    cmd = [TIME, "-v", glide, scene, "--set", f"Output/Directory={out}", "--set", f"Scene name={name}",
           "--set", "Output/Write VTU=false"]
    for s in sets:
        cmd += ["--set", s]
    # The log goes to a file as the run goes (a run takes tens of minutes).
    log_file = os.path.join(out, name + ".log")
    what = f"{study_runs.command_text(cmd[2:])} (log {log_file})"
    with open(log_file, "w") as f:
        try:
            p = study_runs.run(cmd, stdout=f, stderr=subprocess.STDOUT, timeout=limit)
        except subprocess.TimeoutExpired:
            raise study_runs.StudyError(f"{what} was stopped after the --limit of {limit} s") from None
    with open(log_file) as f:
        log = f.read()
    # StudyError unless glide succeeded or a load step failed.
    reason = study_runs.outcome(subprocess.CompletedProcess(cmd, p.returncode, "", log), what)
    finished = reason is None
    if not finished:
        log += f"\nstopped: {reason} ({log_file})"
    d = os.path.join(out, name)
    rows = []
    if os.path.exists(os.path.join(d, "statistics.csv")):
        with open(os.path.join(d, "statistics.csv")) as f:
            rows = list(csv.DictReader(f))
    r = {"key": key, "label": label, "finished": finished, "reached": float(rows[-1]["load_factor"]) if rows else 0.0,
         "log": log}
    for line in log.splitlines():
        if "Maximum resident set size" in line:
            r["memory_mib"] = int(line.split()[-1]) / 1024
        if line.startswith("Degrees of freedom") or "degrees of freedom" in line.lower():
            r.setdefault("dofs_line", line.strip())
    if finished and not (rows and os.path.exists(os.path.join(d, "timings.csv"))):
        raise study_runs.StudyError(f"{what} exited 0 without writing its statistics and timings")
    if os.path.exists(os.path.join(d, "timings.csv")):
        with open(os.path.join(d, "timings.csv")) as f:
            t = {x["quantity"]: x["value"] for x in csv.DictReader(f)}
        r["time"] = float(t["total_wall_time"])
        r["dofs"] = int(t["dofs"])
    if rows:
        its = [int(float(x["kinsol_iterations"])) for x in rows]
        r.update(steps=len(rows), cut_backs=int(float(rows[-1]["cut_backs"])), mean_its=sum(its) / len(its),
                 max_its=max(its))
        steady = [x for x in rows if float(x["load_factor"]) >= STEADY]
        if finished and len(steady) >= 3:
            normal = [abs(float(x["reaction_drive_y"])) for x in steady]
            tangential = [float(x["reaction_drive_x"]) for x in steady]
            mean = sum(normal) / len(normal)
            r.update(mean_normal=mean, ripple=(max(normal) - min(normal)) / mean,
                     tangential_range=(max(tangential) - min(tangential)) / mean)
    return r


def markdown(results, slab, die):
    lines = [f"Slab {slab[0]} x {slab[1]} x {slab[2]} cells (half model), die {die[0]} cells around, "
             f"{die[1]} along its half width, 1 through its thickness.", "",
             "| formulation | reached | steps | cut-backs | Newton its per step (mean / max) | "
             "mean normal force | ripple | tangential range | DoFs | time | peak memory |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in results:
        f = lambda k, fmt: fmt.format(r[k]) if k in r else "-"
        lines.append(f"| {r['label']} | {r['reached']:.3f} | {f('steps', '{}')} | {f('cut_backs', '{}')} | "
                     f"{f('mean_its', '{:.2f}')} / {f('max_its', '{}')} | {f('mean_normal', '{:.4f}')} | "
                     f"{100 * r['ripple']:.1f} % | {100 * r['tangential_range']:.1f} % | " if "ripple" in r else
                     f"| {r['label']} | {r['reached']:.3f} | {f('steps', '{}')} | {f('cut_backs', '{}')} | "
                     f"{f('mean_its', '{:.2f}')} / {f('max_its', '{}')} | - | - | - | ")
        lines[-1] += f"{f('dofs', '{}')} | {f('time', '{:.0f} s')} | {f('memory_mib', '{:.0f} MiB')} |"
    return "\n".join(lines) + "\n"


def main():
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("--glide", required=True)
    a.add_argument("--runs", default="mortar,nts")
    a.add_argument("--output", default=None)
    a.add_argument("--markdown", default=None)
    a.add_argument("--steps", type=int, default=100)
    a.add_argument("--slab", default="36,12,8", help="slab cells in x, y, z (half model)")
    a.add_argument("--die", default="48,13", help="die cells around and along its half width")
    a.add_argument("--limit", type=float, default=None, help="seconds per run")
    args = a.parse_args()
    study_runs.check_binary(TIME, "GNU time (for the peak memory)")
    return study_runs.main(study, args, os.path.abspath(args.glide))


def study(args):
    out = args.output or tempfile.mkdtemp(prefix="glide-ironing3d-")
    slab = [int(x) for x in args.slab.split(",")]
    die = [int(x) for x in args.die.split(",")]
    results = []
    for key in args.runs.split(","):
        r = run(os.path.abspath(args.glide), out, key, slab, die, args.steps, args.limit)
        results.append(r)
        print(f"{key}: finished {r['finished']}, reached {r['reached']:.3f}, "
              f"{ {k: v for k, v in r.items() if k not in ('log', 'label', 'key')} }", flush=True)
        if not r["finished"]:
            print(r["log"][-2000:])
    text = markdown(results, slab, die)
    print(text)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text)
    return 0 if all(r["finished"] for r in results) else 1


if __name__ == "__main__":
    sys.exit(main())
