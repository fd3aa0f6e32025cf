#!/usr/bin/env python3
"""Runs the command in its arguments and parses its standard output as one JSON document
(standard error is passed through): prints 'valid JSON of <scene>' and exits 0, or says why not
and exits 1. For --bench, whose standard output is its JSON alone."""
import json
import subprocess
import sys

run = subprocess.run(sys.argv[1:], stdout=subprocess.PIPE, text=True)
if run.returncode != 0:
    print(f"the command exited with {run.returncode}")
    sys.exit(1)
try:
    doc = json.loads(run.stdout)
except json.JSONDecodeError as e:
    print(f"standard output is not JSON: {e}; it begins {run.stdout[:80]!r}")
    sys.exit(1)
print("valid JSON of", doc.get("scene", "(no scene)"))
