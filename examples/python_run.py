"""A scene run from Python (paste into a notebook): Table 1's Gömböc I for 30 periods, its fingerprint (the one
`gomboc run` prints for the same scene), its angular velocity as numpy arrays, and an error caught.

    PYTHONPATH=python GOMBOC_LIB=build/libgomboc.so.0.1 /usr/bin/python3 examples/python_run.py CASE
(after `make install`, with PREFIX=/usr/local: /usr/bin/python3 examples/python_run.py CASE)"""
import sys

import numpy as np

import gomboc

case = sys.argv[1] if len(sys.argv) > 1 else "cases/table1-gomboc-I.ini"
scene = gomboc.load(case, {"integrator.periods": 60, "strobe.transient_periods": 10})
run = scene.run()
omega = np.column_stack([run.history[k] for k in ("omega_x", "omega_y", "omega_z")])
print(f"fingerprint {run.fingerprint[0]}/{run.fingerprint[1]}; {len(run.history['t'])} samples; "
      f"|omega| at the end {np.linalg.norm(omega[-1]):.6f} rad/s; ledger {run.values['energy_residual']:.3e} J")
try:
    gomboc.loads({"body": {"beta": 0.3}}, name="mine.ini")
except gomboc.GombocError as error:
    print(f"refused: {error.file}:{error.line}: [{error.section}] {error.key} (allowed: {error.allowed})")
