"""The Python package's check (verify/python.c runs it): loads a scene three ways, runs it, prints what the C side
compares with `gomboc run` as JSON on standard output. Arguments: the scene file, a periods override."""
import json
import sys

import gomboc

scene_path, periods = sys.argv[1], int(sys.argv[2])
out = {}
run = gomboc.load(scene_path, {"integrator.periods": periods}).run(impacts=True)
out["fingerprint"] = list(run.fingerprint)
out["samples"] = len(run.history["t"])
out["last"] = {name: float(run.history[name][-1]) for name in ("t", "omega_x", "omega_y", "omega_z", "E", "residual")}
out["values"] = {k: v for k, v in run.values.items() if k != "seconds"}
with open(scene_path, encoding="utf-8") as handle:
    text = handle.read()
out["from_text"] = list(gomboc.loads(text, {"integrator": {"periods": periods}}).run(history=False).fingerprint)
errors = []
for make in (lambda: gomboc.loads({"forcing": {"omega": -3}}, name="bad.ini"),
             lambda: gomboc.load(scene_path, {"forcing.omegas": 3}),
             lambda: gomboc.load(scene_path + ".missing")):
    try:
        make()
        errors.append(None)
    except gomboc.GombocError as e:
        errors.append({"status": e.status, "file": e.file, "line": e.line, "section": e.section, "key": e.key,
                       "allowed": e.allowed, "message": e.message})
out["errors"] = errors
out["columns"] = gomboc.columns()
scene = gomboc.load(scene_path)
props = scene.massprops()
out["massprops"] = [props["volume"]] + list(props["centroid"]) + list(props["inertia"].ravel())
contact = scene.contact([0.6, 0.6, -0.5])
out["contact"] = [contact["phi"], contact["theta"], contact["height"]] + list(contact["rc"])
print(json.dumps(out))
