#!/usr/bin/env python3
"""Input-error test (P4.1): run glide on a faulty scene and check that it
exits with the expected status, prints a message that matches the expected
pattern (naming the file or parameter), and writes nothing: the output
directory must not exist afterwards."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

ap = argparse.ArgumentParser()
ap.add_argument("--glide", required=True)
ap.add_argument("--status", type=int, default=1)
ap.add_argument("--expect", action="append", default=[], help="regex the message must match")
ap.add_argument("args", nargs="*")
a = ap.parse_args()

out = tempfile.mkdtemp(prefix="glide-error-")
shutil.rmtree(out)
cmd = [a.glide] + a.args
if any(x.endswith(".prm") for x in a.args):
    cmd += ["--set", f"Output/Directory={out}"]
run = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
text = run.stdout + run.stderr
print(text)
ok = True
if run.returncode != a.status:
    print(f"FAIL: exit status {run.returncode}, expected {a.status}")
    ok = False
for pattern in a.expect:
    if not re.search(pattern, text, re.S):
        print(f"FAIL: message does not match {pattern!r}")
        ok = False
if "internal error" in text or "Segmentation" in text or "Aborted" in text:
    print("FAIL: crash instead of an input error")
    ok = False
if os.path.exists(out):
    print(f"FAIL: output written to {out}: {os.listdir(out)}")
    ok = False
print("PASSED" if ok else "FAILED")
sys.exit(0 if ok else 1)
