#!/usr/bin/env python3
"""Hertz line contact study (Case A of reference/benchmarks.md; issue 3,
section 6): the scene parameters/hertz-2d.prm on a sequence of meshes
refined towards the contact (the scene's 'Minimum refinement radius' makes
the finest cells cover more than twice the contact zone). For each mesh: the contact half-width a_h
(midpoint between the last closed and the first open slave node), the peak
pressure p0_h (largest nodal CPRESS), the relative L2 error of the pressure
on the contact boundary (piecewise linear interpolant of the nodal
pressures against p0 sqrt(1 - (x/a)^2), integrated with Gauss quadrature on
every node interval, split at +-a), and the Newton iterations per step.

Why the expected answer is right: a = sqrt(4 P R*/(pi E*)) and p0 =
2P/(pi a) are Hertz's closed form for a cylinder on a rigid flat; a/R =
0.034 is small, so half-space theory holds. The pressure has a square-root
edge at +-a, so its L2 error converges at about order 1 under refinement
(per-level rates scatter, so the rate is fitted over all levels).

Checks: on the finest mesh |p0_h/p0 - 1| <= 2 % and |a_h/a - 1| <= 3 %;
the fitted L2 rate is at least 0.7; every load step converges without
cut-back in at most 15 Newton iterations (measured on 2026-11-22: at most 2
to 8 per step from the coarsest to the finest mesh; the first step, which
starts from contact at a single node, needs the most).
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "study"))
import study_runs  # noqa: E402  (glide's exit statuses; children stopped with this script)

E_STAR = 1.0 / (1 - 0.3 ** 2)
P, R = 1.0e-3, 1.0
A = math.sqrt(4 * P * R / (math.pi * E_STAR))
P0 = 2 * P / (math.pi * A)
GAUSS = [(-math.sqrt(3 / 5), 5 / 9), (0.0, 8 / 9), (math.sqrt(3 / 5), 5 / 9)]


def exact(x):
    return P0 * math.sqrt(1 - (x / A) ** 2) if abs(x) < A else 0.0


def l2_error(xs, ps):
    err = 0.0
    for (x0, p0), (x1, p1) in zip(zip(xs, ps), zip(xs[1:], ps[1:])):
        cuts = [x0] + [c for c in (-A, A) if x0 < c < x1] + [x1]
        for a, b in zip(cuts, cuts[1:]):
            for s, w in GAUSS:
                x = 0.5 * (a + b) + 0.5 * (b - a) * s
                ph = p0 + (p1 - p0) * (x - x0) / (x1 - x0)
                err += 0.5 * (b - a) * w * (ph - exact(x)) ** 2
    return math.sqrt(err) / math.sqrt(4.0 / 3.0 * A * P0 ** 2)


def zigzag_of(xs, ps):
    """Node-to-node zigzag of the nodal pressures in the central half of
    the contact zone, |x| <= a/2: the largest deviation of p_i from the
    straight line through its neighbours, less that of the Hertz profile
    (whose curvature alone gives such a deviation on coarse meshes), over
    p0."""
    def bend(x0, x1, x2, p0_, p1, p2):
        return p1 - (p0_ + (p2 - p0_) * (x1 - x0) / (x2 - x0))
    worst = float("nan")
    if sum(1 for x in xs if abs(x) <= 0.5 * A) < 3:
        return worst  # the central half holds fewer than 3 nodes: not resolved
    for i in range(1, len(xs) - 1):
        if abs(xs[i]) <= 0.5 * A:
            d = bend(xs[i - 1], xs[i], xs[i + 1], ps[i - 1], ps[i], ps[i + 1]) - \
                bend(xs[i - 1], xs[i], xs[i + 1], exact(xs[i - 1]), exact(xs[i]), exact(xs[i + 1]))
            worst = abs(d) / P0 if math.isnan(worst) else max(worst, abs(d) / P0)
    return worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--glide", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--levels", default="3,4,5,6,7")
    ap.add_argument("--degree", type=int, default=1)
    ap.add_argument("--output", default="study-output")
    ap.add_argument("--table", help="write the table (CSV) here")
    ap.add_argument("--elastic", action="store_true",
                    help="the scene is hertz-2d-elastic.prm: elastic block as the master (1/E* = 2 (1 - nu^2)/E); "
                         "the block is refined with the cylinder (two levels fewer)")
    ap.add_argument("--smoothing", help="override the pair's 'Smoothing fraction'")
    ap.add_argument("--sliding", help="override the pair's 'Sliding' (finite or small)")
    ap.add_argument("--set", action="append", default=[], dest="sets",
                    help="further parameter override 'path=value' (repeatable), e.g. the formulation")
    ap.add_argument("--p0-tolerance", type=float, default=0.02, help="|p0_h/p0 - 1| allowed on the finest mesh")
    ap.add_argument("--a-tolerance", type=float, default=0.03, help="|a_h/a - 1| allowed on the finest mesh")
    ap.add_argument("--max-zigzag", type=float,
                    help="if given: largest node-to-node zigzag of the pressure allowed: the deviation of a "
                         "nodal pressure from the straight line through its two neighbours, less that of the "
                         "Hertz profile, over p0, in the central half |x| <= a/2 of the contact zone; checked on "
                         "every mesh with at least 3 nodes there, and at least 3 such meshes are required")
    ap.add_argument("--resolved-only", action="store_true",
                    help="apply --max-iterations only to meshes on which the first load step's contact "
                         "half-width (a/2 at a quarter of the load) is at least one slave facet h; on "
                         "coarser ones require convergence without cut-back and print the count")
    ap.add_argument("--max-iterations", type=int, default=15,
                    help="bar for the Newton iterations of every load step")
    ap.add_argument("--keep-going", action="store_true",
                    help="record a level on which a load step fails (glide's exit status 2: the level and "
                         "glide's reason, one per line, in TABLE.failed) instead of stopping; any other "
                         "failure of glide stops the study (exit status 2)")
    a = ap.parse_args()
    study_runs.main(study, a, a.glide)


def study(a):
    global E_STAR, A, P0
    if a.elastic:
        E_STAR = 1.0 / (2 * (1 - 0.3 ** 2))
        A = math.sqrt(4 * P * R / (math.pi * E_STAR))
        P0 = 2 * P / (math.pi * A)

    for stale in ([a.table, a.table + ".failed"] if a.table else []):
        if os.path.exists(stale):
            os.remove(stale)  # a table of an earlier run must not pass for this one's
    rows = []
    for level in [int(x) for x in a.levels.split(",")]:
        name = f"hertz-q{a.degree}-l{level}"
        cmd = [a.glide, a.scene, "--set", f"Output/Directory={a.output}", "--set", f"Scene name={name}",
               "--set", f"Body cylinder/Refinement/Local refinements={level}",

               "--set", f"Discretization/Element degree={a.degree}", "--set", "Output/Write VTU=false"]
        if a.elastic:
            cmd += ["--set", f"Body block/Refinement/Local refinements={max(level - 2, 0)}"]
        if a.smoothing is not None:
            cmd += ["--set", f"Contact pair hertz/Smoothing fraction={a.smoothing}"]
        if a.sliding is not None:
            cmd += ["--set", f"Contact pair hertz/Sliding={a.sliding}"]
        for extra in a.sets:
            cmd += ["--set", extra]
        what = f"glide {os.path.basename(a.scene)} at level {level} ({', '.join(cmd[i + 1] for i in range(2, len(cmd), 2))})"
        run = study_runs.run(cmd)
        reason = study_runs.outcome(run, what)  # StudyError unless it converged or a load step failed
        if reason is not None and a.keep_going:
            print(f"level {level} failed: {reason}")
            rows.append(dict(level=level, failed=True, reason=reason))
            continue
        if reason is not None:
            print(run.stdout[-4000:], run.stderr[-4000:])
            sys.exit(f"glide failed at level {level}: {reason}")
        out = os.path.join(a.output, name)
        if not os.path.exists(os.path.join(out, "statistics.csv")):
            raise study_runs.StudyError(f"{what} exited 0 without writing {os.path.join(out, 'statistics.csv')}")
        with open(os.path.join(out, "statistics.csv")) as f:
            stats = list(csv.DictReader(f))
        last = sorted(x for x in os.listdir(out) if x.startswith("contact-hertz-"))[-1]
        with open(os.path.join(out, last)) as f:
            nodes = sorted(csv.DictReader(f), key=lambda r: float(r["X"]))
        xs = [float(r["X"]) for r in nodes]
        ps = [float(r["CPRESS"]) for r in nodes]
        closed = [float(r["X"]) for r in nodes if r["CSTATUS"] == "1"]
        right = max(closed)
        first_open = min(x for x in xs if x > right)
        a_h = 0.5 * (right + first_open)
        h = min(x1 - x0 for x0, x1 in zip(xs, xs[1:]) if abs(x0) < A)
        with open(os.path.join(out, "timings.csv")) as f:
            t = {r["quantity"]: float(r["value"]) if r["quantity"] not in ("linear_solver",) else 0
                 for r in csv.DictReader(f)}
        zigzag = zigzag_of(xs, ps)
        rows.append(dict(level=level, h=h, dofs=int(stats[-1]["dofs"]), a_ratio=a_h / A, p0_ratio=max(ps) / P0,
                         zigzag=zigzag,
                         l2=l2_error(xs, ps), its=[int(s["kinsol_iterations"]) for s in stats],
                         cutbacks=int(stats[-1]["cut_backs"]), time=t["total_wall_time"],
                         memory=t["peak_memory_mib"]))

    failed = [r for r in rows if r.get("failed")]
    rows = [r for r in rows if not r.get("failed")]
    if a.table and failed:
        with open(a.table + ".failed", "w") as f:
            f.write("".join(f"{r['level']}\t{r['reason']}\n" for r in failed))
    if not rows:
        sys.exit("every level failed")
    print(f"{'level':>5} {'h':>9} {'DoFs':>7} {'a_h/a':>8} {'p0_h/p0':>8} {'L2 rel':>9} {'rate':>5} "
          f"{'zigzag':>7} {'its/step':>12} {'time':>6} {'MiB':>6}")
    for i, r in enumerate(rows):
        rate = "" if i == 0 else f"{math.log(rows[i-1]['l2'] / r['l2']) / math.log(rows[i-1]['h'] / r['h']):5.2f}"
        print(f"{r['level']:5d} {r['h']:9.2e} {r['dofs']:7d} {r['a_ratio']:8.4f} {r['p0_ratio']:8.4f} "
              f"{r['l2']:9.3e} {rate:>5} {100 * r['zigzag']:6.2f}% {str(r['its']):>12} {r['time']:6.2f} "
              f"{r['memory']:6.0f}")
    xs = [math.log(r["h"]) for r in rows]
    ys = [math.log(r["l2"]) for r in rows]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    rate = (sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sum((x - mx) ** 2 for x in xs)
            if len(rows) > 1 else float("nan"))
    fin = rows[-1]
    print(f"fitted L2 rate {'- (one level)' if len(rows) < 2 else f'{rate:.3f}'}; finest mesh: p0_h/p0 = {fin['p0_ratio']:.4f}, a_h/a = {fin['a_ratio']:.4f}")
    if a.table:
        with open(a.table, "w") as f:
            w = csv.writer(f)
            w.writerow(["level", "h", "dofs", "a_ratio", "p0_ratio", "l2_rel", "max_its", "mean_its", "time_s",
                        "memory_mib", "zigzag"])
            for r in rows:
                w.writerow([r["level"], r["h"], r["dofs"], r["a_ratio"], r["p0_ratio"], r["l2"], max(r["its"]),
                            sum(r["its"]) / len(r["its"]), r["time"], r["memory"], r["zigzag"]])
    ok = True
    checks = [(abs(fin["p0_ratio"] - 1) <= a.p0_tolerance, f"p0 within {100 * a.p0_tolerance:g} %"),
              (abs(fin["a_ratio"] - 1) <= a.a_tolerance, f"a within {100 * a.a_tolerance:g} %")]
    if a.max_zigzag is not None:
        resolved = [r["zigzag"] for r in rows if not math.isnan(r["zigzag"])]
        checks.append((len(resolved) >= 3 and all(z <= a.max_zigzag for z in resolved),
                       f"zigzag at most {100 * a.max_zigzag:g} % on every mesh with at least 3 nodes in "
                       f"the central half ({len(resolved)} meshes)"))
    if len(a.levels.split(",")) < 2:
        print("no L2 rate: one level asked for (not checked)")
    elif len(rows) < 2:
        checks.append((False, f"fitted L2 rate: only {len(rows)} of the levels converged"))
    else:
        checks.append((rate >= 0.7, "fitted L2 rate >= 0.7"))
    for cond, msg in checks + [
                      (all(r["cutbacks"] == 0 and (max(r["its"]) <= a.max_iterations or
                                                   (a.resolved_only and 0.5 * A < r["h"])) for r in rows),
                       f"every step converges without cut-back in <= {a.max_iterations} iterations"
                       + (" (on meshes that resolve the first step's contact zone)" if a.resolved_only else ""))]:
        print(("ok:   " if cond else "FAIL: ") + msg)
        ok = ok and cond
    print("PASSED" if ok else "FAILED")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
