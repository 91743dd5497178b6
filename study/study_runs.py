"""How the study scripts run glide and each other (study/*.py and
tests/studies/hertz_study.py import this module).

glide's exit status (source/main.cc): 0 success, 1 input error, 2 a load
step failed, 3 internal error, 4 input/output error, 128 + n stopped by
signal n. Only 2 is a result a study may publish ("did not converge",
with glide's own reason); every other failure, a missing binary and a
time limit are failures of the study itself: outcome() raises StudyError,
and the script stops without writing its report (exit status
STUDY_FAILED).

Children run in their own process group; stop_children_on_signals() makes
SIGTERM and SIGINT stop them (and their children) before the script exits
with 128 + the signal number.
"""
import os
import signal
import subprocess
import sys
import threading

# Exit status of a study script whose measurement failed (nothing written).
STUDY_FAILED = 2

_children = set()
_lock = threading.RLock()  # the signal handler may run while the main thread holds it
_stopping = []


class StudyError(Exception):
    """A run that failed for another reason than a load step that did not
    converge: the study cannot publish anything from it."""


def check_binary(path, what="the glide binary"):
    """Stop (exit status STUDY_FAILED) unless path is an executable file."""
    if not os.path.isfile(path) or not os.access(path, os.X_OK):
        print(f"{os.path.basename(sys.argv[0])}: {what} {path!r} "
              f"{'is not executable' if os.path.isfile(path) else 'does not exist'}; nothing was run or written",
              file=sys.stderr)
        sys.exit(STUDY_FAILED)


def _kill_group(p, sig):
    try:
        os.killpg(p.pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def _handler(signum, frame):
    _stopping.insert(0, signum)
    with _lock:
        children = list(_children)
    for p in children:
        _kill_group(p, signal.SIGTERM)
    print(f"{os.path.basename(sys.argv[0])}: stopped by signal {signum}; stopped its runs, wrote nothing",
          file=sys.stderr, flush=True)
    raise SystemExit(128 + signum)


def stop_children_on_signals():
    for s in (signal.SIGTERM, signal.SIGINT):
        signal.signal(s, _handler)


def stop_all():
    """Stop every running child and refuse to start new ones (after a
    failure that ends the study, while other threads still run glide)."""
    _stopping.append(None)
    with _lock:
        children = list(_children)
    for p in children:
        _kill_group(p, signal.SIGTERM)


def run(cmd, timeout=None, **kw):
    """subprocess.run(cmd, capture_output=True, text=True) (stdout and
    stderr may be redirected by kw) with the child in its own process
    group, which is stopped with the script. A missing program raises
    StudyError, a time limit subprocess.TimeoutExpired (the child
    stopped)."""
    if _stopping:
        if _stopping[0] is None:
            raise StudyError(f"not started after an earlier failure: {command_text(cmd)}")
        raise SystemExit(128 + _stopping[0])
    kw.setdefault("stdout", subprocess.PIPE)
    kw.setdefault("stderr", subprocess.PIPE)
    try:
        p = subprocess.Popen(cmd, text=True, start_new_session=True, **kw)
    except OSError as e:
        raise StudyError(f"cannot run {command_text(cmd)}: {e}") from None
    with _lock:
        _children.add(p)
    try:
        out, err = p.communicate(timeout=timeout)
    except BaseException:
        _kill_group(p, signal.SIGTERM)
        try:
            p.wait(5)
        except subprocess.TimeoutExpired:
            _kill_group(p, signal.SIGKILL)
        p.wait()
        raise
    finally:
        with _lock:
            _children.discard(p)
    return subprocess.CompletedProcess(cmd, p.returncode, out or "", err or "")


def command_text(cmd):
    return " ".join(f"'{x}'" if " " in x or not x else x for x in cmd)


def error_line(text):
    """glide's own reason in its output: the line that starts with
    'glide: error:' (the prefix dropped), else one that says a load step
    failed; None if there is neither."""
    lines = [x.strip() for x in text.splitlines() if x.strip()]
    for x in lines:
        if x.startswith("glide: error:"):
            return x[len("glide: error:"):].strip()
    for x in lines:
        if x.startswith("load step ") and " failed" in x:
            return x
    return None


def describe(p):
    """The exit status (or signal) and glide's message, for a failed run."""
    status = (f"stopped by signal {-p.returncode}" if p.returncode < 0 else
              f"exit status {p.returncode}")
    lines = [x for x in (p.stderr + "\n" + p.stdout).splitlines() if x.strip()]
    message = next((x for x in lines if x.startswith("glide:")), None)
    if message is None:
        message = " / ".join(x.strip() for x in lines[-3:]) or "no output"
    return f"{status}: {message}"


def outcome(p, what):
    """None if the run p succeeded; glide's reason if a load step failed
    (exit status 2 with glide's message); otherwise StudyError naming the
    run (what) and glide's message."""
    if p.returncode == 0:
        return None
    if p.returncode == 2:
        reason = error_line(p.stderr) or error_line(p.stdout)
        if reason:
            return reason
    raise StudyError(f"{what} failed ({describe(p)})")


def report_study_error(e):
    """Print e and exit with STUDY_FAILED."""
    print(f"{os.path.basename(sys.argv[0])}: the study failed, nothing was written: {e}", file=sys.stderr)
    sys.exit(STUDY_FAILED)


def main(study, a, glide):
    """A study script's main part: check the glide binary, stop the
    children with the script, and return study(a); a StudyError ends the
    script with its message (report_study_error)."""
    check_binary(glide)
    stop_children_on_signals()
    try:
        return study(a)
    except StudyError as e:
        report_study_error(e)
