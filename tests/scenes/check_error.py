#!/usr/bin/env python3
"""Bad-input and fault test (P4.1, P5.1, issue 13): run glide on a faulty
scene, command line or environment and check that it exits with the expected
status within a time limit (a hang fails the test), prints a message that
matches the expected pattern (naming the file or parameter and what to do),
does not crash, and leaves the file system as it should:

- input errors (the default): nothing is written, the output directory must
  not exist afterwards;
- --setup: an output directory prepared beforehand (a file where the
  directory should be, files of the user's in it, ...); the user's files
  must be unchanged afterwards and nothing else may appear;
- --fault: a fault during a run (SIGTERM, SIGKILL, SIGUSR1, SIGXCPU,
  SIGQUIT, a full disk, the file size limit); then every
  file under its final name must be complete (.vtu/.pvd end with
  </VTKFile>, CSV rows are whole), every .pvd and statistics.csv must list
  the same load steps, every file an index lists must exist, and no *.tmp
  file may be left (after SIGKILL, which no program can catch, stray .tmp
  files and the staging directory are tolerated if no index lists them, and
  a second run in the same directory must remove them; a .pvd may list the
  one step after those of statistics.csv, which is renamed last).

Exit status 0 pass, 1 fail, 77 skipped (a test that cannot run here, e.g. a
permission test as root or a disk-full test where mounting is not allowed;
ctest registers 77 as SKIP_RETURN_CODE, so a skip never counts as a pass).
"""
import argparse
import csv
import os
import re
import shlex
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time

SKIP = 77

ap = argparse.ArgumentParser()
ap.add_argument("--glide", required=True)
ap.add_argument("--status", type=int, default=1, help="expected exit status")
ap.add_argument("--expect", action="append", default=[], help="regex the message must match")
ap.add_argument("--timeout", type=float, default=60, help="seconds before the run counts as a hang")
ap.add_argument("--name", help="scene name (default: the scene file's stem)")
ap.add_argument("--setup", default="none",
                choices=["none", "file", "under-file", "foreign", "foreign-glide-name", "unwritable",
                         "rerun-with-user-file"],
                help="prepare the output directory before the run")
ap.add_argument("--stdout", default="pipe", choices=["pipe", "closed", "full"])
ap.add_argument("--mpirun", help="MPI launcher command, e.g. 'mpirun -np 2'")
ap.add_argument("--copy-scene-as", help="run a copy of the scene file under this file name")
ap.add_argument("--fault", choices=["sigterm", "sigkill", "disk-full", "sigusr1", "sigxcpu", "sigquit",
                                    "file-size-limit"])
ap.add_argument("--file-size-limit", type=int, default=200, help="KiB, for --fault file-size-limit")
ap.add_argument("--after-rows", type=int, default=3, help="kill after this many statistics rows")
ap.add_argument("--disk-size", default="160k", help="size of the tmpfs for --fault disk-full")
ap.add_argument("--memory-limit", type=int, help="address-space limit of the run in MiB (out-of-memory tests)")
ap.add_argument("--refused-at-setup", action="store_true",
                help="with --memory-limit: the scene is refused before anything is written")
ap.add_argument("args", nargs="*")
a = ap.parse_args()
# CMake splits arguments at ';', so tests write it as %3B (as in a URL).
a.args = [x.replace("%3B", ";") for x in a.args]
a.expect = [x.replace("%3B", ";") for x in a.expect]

failures = []


def check(condition, message):
    print(("ok:   " if condition else "FAIL: ") + message)
    if not condition:
        failures.append(message)


def skip(message):
    print(f"SKIPPED: {message}")
    sys.exit(SKIP)


work = tempfile.mkdtemp(prefix="glide-bad-input-")
out = os.path.join(work, "output")
args = list(a.args)
scene_files = [x for x in args if x.endswith(".prm")]
if a.copy_scene_as and scene_files:
    copy = os.path.join(work, a.copy_scene_as)
    shutil.copy(scene_files[0], copy)
    args[args.index(scene_files[0])] = copy
    scene_files = [copy]
name = a.name or (os.path.splitext(os.path.basename(scene_files[0]))[0] if scene_files else "")
mounted = False


def glide_command(output):
    # The output directory first: the test's own --set (and a --set that
    # lacks its argument) come after it.
    cmd = [a.glide] + (["--set", f"Output/Directory={output}"] if scene_files else []) + args
    if a.mpirun:
        cmd = shlex.split(a.mpirun) + cmd
    return cmd


def cleanup():
    if mounted:
        subprocess.run(["umount", out], capture_output=True)
    for root, dirs, _ in os.walk(work):
        for d in dirs:
            try:
                os.chmod(os.path.join(root, d), 0o755)
            except OSError:
                pass
    shutil.rmtree(work, ignore_errors=True)


# --- what the output directory holds before the run ------------------------
user_files = {}
if a.setup == "file":
    with open(out, "w") as f:
        f.write("a file of the user's\n")
    user_files[out] = open(out).read()
elif a.setup == "under-file":
    os.makedirs(work, exist_ok=True)
    parent = os.path.join(work, "afile")
    with open(parent, "w") as f:
        f.write("a file of the user's\n")
    user_files[parent] = open(parent).read()
    out = os.path.join(parent, "sub")
elif a.setup in ("foreign", "foreign-glide-name"):
    os.makedirs(os.path.join(out, name))
    f = os.path.join(out, name, "notes.txt" if a.setup == "foreign" else "statistics.csv")
    with open(f, "w") as g:
        g.write("the user's own notes\n")
    user_files[f] = open(f).read()
elif a.setup == "unwritable":
    os.makedirs(out)
    os.chmod(out, stat.S_IRUSR | stat.S_IXUSR)
    probe = os.path.join(out, "probe")
    try:
        open(probe, "w").close()
        os.remove(probe)
        cleanup()
        skip("this user (root?) can write into a read-only directory; the permission test cannot run here")
    except OSError:
        pass
elif a.setup == "rerun-with-user-file":
    first = subprocess.run(glide_command(out), capture_output=True, text=True, timeout=a.timeout)
    if first.returncode != 0:
        print(first.stdout + first.stderr)
        check(False, f"first run exited with {first.returncode}")
    f = os.path.join(out, name, "notes.txt")
    with open(f, "w") as g:
        g.write("the user's own notes, added to glide's directory\n")
    user_files[f] = open(f).read()
elif a.fault == "disk-full":
    os.makedirs(out)
    m = subprocess.run(["mount", "-t", "tmpfs", "-o", f"size={a.disk_size}", "tmpfs", out],
                       capture_output=True, text=True)
    if m.returncode != 0:
        cleanup()
        skip(f"cannot mount a small tmpfs for the disk-full test ({m.stderr.strip()})")
    mounted = True


def stdout_target():
    if a.stdout == "full":
        return open("/dev/full", "w")
    return subprocess.PIPE


def preexec():
    if a.stdout == "closed":
        os.close(1)


# --- the run -----------------------------------------------------------------
cmd = glide_command(out)
print("$ " + " ".join(shlex.quote(c) for c in cmd))
start = time.time()
def limit_memory():
    import resource
    limit = a.memory_limit * 1024 * 1024
    resource.setrlimit(resource.RLIMIT_AS, (limit, limit))


def limit_file_size():
    import resource
    limit = a.file_size_limit * 1024
    resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))


def before_exec():
    if a.stdout == "closed":
        preexec()
    if a.memory_limit:
        limit_memory()
    if a.fault == "file-size-limit":
        limit_file_size()


SIGNALS = {"sigterm": signal.SIGTERM, "sigkill": signal.SIGKILL, "sigusr1": signal.SIGUSR1,
           "sigxcpu": signal.SIGXCPU, "sigquit": signal.SIGQUIT}


p = subprocess.Popen(cmd, stdout=stdout_target(), stderr=subprocess.PIPE, text=True,
                     preexec_fn=before_exec if (a.stdout == "closed" or a.memory_limit
                                                or a.fault == "file-size-limit") else None)
if a.fault in SIGNALS:
    stats = os.path.join(out, name, "statistics.csv")
    deadline = time.time() + a.timeout
    while time.time() < deadline and p.poll() is None:
        if os.path.exists(stats) and open(stats).read().count("\n") >= a.after_rows + 1:
            break
        time.sleep(0.02)
    check(p.poll() is None, "glide was still running when the signal was sent")
    p.send_signal(SIGNALS[a.fault])
try:
    stdout, stderr = p.communicate(timeout=a.timeout)
except subprocess.TimeoutExpired:
    p.kill()
    stdout, stderr = p.communicate()
    print((stdout or "") + (stderr or ""))
    check(False, f"glide did not end within {a.timeout} s (a hang)")
    cleanup()
    sys.exit(1)
text = (stdout or "") + (stderr or "")
print(text[-6000:])
print(f"(ran {time.time() - start:.1f} s)")
status = -signal.SIGKILL if a.fault == "sigkill" else a.status
check(p.returncode == status, f"exit status {p.returncode}, expected {status}")
for pattern in a.expect:
    check(re.search(pattern, text, re.S) is not None, f"message matches {pattern!r}")
check(not re.search(r"internal error|Segmentation|Aborted|stacktrace|Stacktrace|terminate called|"
                    r"AddressSanitizer|runtime error:", text),
      "no crash, stack trace or sanitizer report")


# --- the file system afterwards ----------------------------------------------
def complete(path):
    """Whether the file under its final name is complete."""
    data = open(path, "rb").read()
    if path.endswith((".vtu", ".pvd")):
        return data.rstrip().endswith(b"</VTKFile>")
    if path.endswith(".csv"):
        if not data.endswith(b"\n"):
            return False
        lines = data.decode().split("\n")[:-1]
        return all(l.count(",") == lines[0].count(",") for l in lines)
    return len(data) > 0


def pvd_steps(path):
    text = open(path).read()
    return [(float(t), f) for t, f in re.findall(r'timestep="([^"]+)"[^>]*file="([^"]+)"', text)]


def check_consistent(directory, tolerate_stray):
    """Every final-name file complete, indexes agree, no .tmp (see above)."""
    if not os.path.isdir(directory):
        check(False, f"{directory} exists")
        return
    names = sorted(os.listdir(directory))
    print("files:", " ".join(names))
    referenced = set()
    stats = os.path.join(directory, "statistics.csv")
    steps = None
    if os.path.exists(stats):
        check(complete(stats), "statistics.csv is complete")
        with open(stats) as f:
            steps = sorted(round(float(r["load_factor"]), 9) for r in csv.DictReader(f))
        check(len(steps) >= 1, f"statistics.csv lists {len(steps)} step(s)")
    pvds = [n for n in names if n.endswith(".pvd")]
    for pvd in pvds:
        path = os.path.join(directory, pvd)
        check(complete(path), f"{pvd} is complete")
        records = pvd_steps(path)
        for _, f in records:
            referenced.add(f)
            check(os.path.exists(os.path.join(directory, f)), f"{pvd} lists {f}, which exists")
        listed = sorted(round(t, 9) for t, _ in records)
        known = steps if steps is not None else []
        if listed == known:
            check(True, f"{pvd} lists the steps of statistics.csv ({len(records)} vs {len(known)})")
        else:
            # statistics.csv is renamed last in a step's commit: a SIGKILL
            # between the renames leaves a .pvd with the one step being
            # committed more, never fewer steps and never any other.
            one_ahead = (len(listed) == len(known) + 1 and listed[:-1] == known
                         and (not known or listed[-1] > known[-1]))
            check(tolerate_stray and one_ahead,
                  f"{pvd} lists the steps of statistics.csv ({len(records)} vs {len(known)})"
                  + (" or, after SIGKILL inside a commit, the one step after them" if tolerate_stray else ""))
    if steps is None and not tolerate_stray:
        check(not pvds, "no .pvd without statistics.csv")
    for n in names:
        path = os.path.join(directory, n)
        if n.endswith(".tmp") or n == ".glide-staging":
            check(tolerate_stray and n not in referenced,
                  f"{n} left behind" + (" (tolerated after SIGKILL: no index lists it)" if tolerate_stray else ""))
            continue
        if os.path.isfile(path):
            check(complete(path), f"{n} is complete")
    try:
        import vtk
        for f in sorted(referenced)[-2:]:
            r = vtk.vtkXMLUnstructuredGridReader()
            r.SetFileName(os.path.join(directory, f))
            r.Update()
            check(r.GetOutput().GetNumberOfPoints() > 0, f"VTK reads {f}")
    except ImportError:
        print("(python3-vtk9 missing: VTK read check left out)")


if a.fault or (a.status == 2 and a.setup == "none") or (a.memory_limit and not a.refused_at_setup):
    # A run that started (a fault, a failed load step, memory that ran
    # out): complete steps only.
    directory = os.path.join(out, name)
    check_consistent(directory, tolerate_stray=(a.fault == "sigkill"))
    if a.fault == "sigkill":
        # The next run in the same directory removes the stray files.
        again = glide_command(out) + ["--set", "Load stepping/Number of steps=1"]
        r = subprocess.run(again, capture_output=True, text=True, timeout=a.timeout)
        check(r.returncode == 0, f"a second run in the same directory exits with 0 ({r.returncode})")
        check_consistent(directory, tolerate_stray=False)
elif a.setup == "none" and a.stdout == "pipe" or a.setup == "unwritable":
    left = os.listdir(out) if os.path.isdir(out) else []
    check(not left and (a.setup == "unwritable" or not os.path.exists(out)),
          f"nothing written ({out}: {left})")
else:
    for f, content in user_files.items():
        check(os.path.isfile(f) and open(f).read() == content, f"the user's file {f} is unchanged")
    if a.setup in ("foreign", "foreign-glide-name"):
        left = sorted(os.listdir(os.path.join(out, name)))
        check(left == [os.path.basename(f) for f in user_files], f"nothing else written ({left})")

cleanup()
print("PASSED" if not failures else "FAILED")
sys.exit(0 if not failures else 1)
