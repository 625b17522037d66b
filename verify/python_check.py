"""The Python package's check (verify/python.c runs it): loads a scene three ways, runs it, prints what the C side
compares with `gomboc run` as JSON on standard output, and runs a 2 x 2 scan of it in DIR (its CSV there as
python-scan.csv, beside the scan file tiny.ini for the command). Arguments: the scene file, a periods override, DIR."""
import json
import os
import sys

import gomboc

scene_path, periods, folder = sys.argv[1], int(sys.argv[2]), sys.argv[3]
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
equilibria = scene.equilibria()
out["equilibria"] = [[str(t), float(p), float(q), float(r)] for t, p, q, r in
                     zip(equilibria["type"], equilibria["phi"], equilibria["theta"], equilibria["r"])]
out["equilibria_counts"] = equilibria["counts"]
tangle = scene.tangle(0.05)
out["tangle"] = [tangle["homoclinic_orbits"], tangle["smallest_angle"]] + list(tangle["multipliers"])
try:
    scene.tangle(0.5)
    out["tangle_refused"] = None
except gomboc.GombocError as e:
    out["tangle_refused"] = e.message
tiny = os.path.join(folder, "tiny.ini")
with open(tiny, "w", encoding="utf-8") as handle:
    handle.write(f"[scan]\ndescription = the Python package's 2 x 2 check\nbase = {os.path.abspath(scene_path)}\n"
                 "periods = 30\ntransient_periods = 5\nmetrics = all\n[x]\nkey = forcing.omega\nfrom = 12\nto = 24\n"
                 "count = 2\nscale = linear\n[y]\nkey = forcing.A1\nfrom = 0\nto = 4\ncount = 2\nscale = linear\n")
heard = []
csv, table = gomboc.scan(tiny, threads=2, progress=lambda *args: heard.append(args))
with open(os.path.join(folder, "python-scan.csv"), "w", encoding="utf-8") as handle:
    handle.write(csv)
# the margins of each point of the scan, from its scene (the base with the point's omega and A1)
out["melnikov"] = [list(gomboc.load(scene_path, {"forcing.omega": float(w), "forcing.A1": float(a)}).melnikov().values())
                   for w, a in zip(table["forcing.omega"], table["forcing.A1"])]
out["scan"] = {"points": len(table["index"]), "progress_calls": len(heard),
               "phases": sorted({phase for phase, *_ in heard}), "lambda_max": list(table["lambda_max"])}
import gomboc.plot  # noqa: E402

figure = gomboc.plot.scan(os.path.join(folder, "python-scan.csv"), ["lambda_max"], out=os.path.join(folder, "scan.png"))
page = gomboc.plot.run(folder, ["table1"])  # the command's run of the scene, written there before this script
try:
    gomboc.plot.scan(os.path.join(folder, "python-scan.csv"), ["nonesuch"])
    refused = None
except gomboc.GombocError as e:
    refused = e.message
out["plot"] = {"figure": figure, "figure_bytes": os.path.getsize(figure) if os.path.exists(figure) else 0, "page": page,
               "page_bytes": os.path.getsize(page) if os.path.exists(page) else 0, "refused": refused}
print(json.dumps(out))
