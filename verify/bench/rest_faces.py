"""make bench: the rest faces of a large polyhedron, near-linear in its faces.

`gomboc shape --mesh` on Fibonacci spheres of 2 000 to 20 000 vertices (convex, every vertex on the hull; the
faces written outward by scipy's ConvexHull): each whole process timed (the best of three wall times, so that
a noisy machine's slow run does not count), and the growth exponent fitted over the sizes, log t against
log n. Targets (issue 52): 20 000 vertices in under 2 s, and an exponent below 1.5 (the pairwise search it
replaced was quadratic: 2 000 vertices 1.8 s, 20 000 more than 300 s). Writes a JSON of the measurements;
exits 1 when a target is missed.

    python3 verify/bench/rest_faces.py GOMBOC OUT.json
"""
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy
from scipy.spatial import ConvexHull

SIZES = (2000, 5000, 20000)
TARGET_SECONDS, TARGET_EXPONENT = 2.0, 1.5


def fibonacci_sphere(n):
    i = numpy.arange(n) + 0.5
    z = 1 - 2 * i / n
    r = numpy.sqrt(1 - z * z)
    angle = math.pi * (1 + 5 ** 0.5) * i
    return numpy.c_[r * numpy.cos(angle), r * numpy.sin(angle), z]


def write_off(path, points):
    hull = ConvexHull(points)
    with open(path, "w", encoding="ascii") as f:
        f.write(f"OFF\n{len(points)} {len(hull.simplices)} 0\n")
        f.writelines(f"{x:.17g} {y:.17g} {z:.17g}\n" for x, y, z in points)
        for simplex, equation in zip(hull.simplices, hull.equations):
            a, b, c = points[simplex]
            if numpy.dot(numpy.cross(b - a, c - a), equation[:3]) < 0:
                simplex = simplex[[0, 2, 1]]
            f.write("3 %d %d %d\n" % tuple(simplex))


def main(gomboc, out):
    rows = []
    with tempfile.TemporaryDirectory() as d:
        for n in SIZES:
            path = os.path.join(d, f"fib{n}.off")
            write_off(path, fibonacci_sphere(n))
            times, faces = [], None
            for _ in range(3):
                start = time.perf_counter()
                done = subprocess.run([gomboc, "shape", "--mesh", path, "--json"], capture_output=True, text=True)
                times.append(time.perf_counter() - start)
                if done.returncode:
                    sys.exit(f"rest_faces: gomboc shape --mesh {path} failed: {done.stderr.strip()}")
                faces = json.loads(done.stdout)["rest_face_count"]
            rows.append({"vertices": n, "seconds": min(times), "rest_faces": faces})
            print(f"bench: rest faces of a {n}-vertex polyhedron: {min(times):.3f} s (whole process, best of 3), {faces} faces")
    x = numpy.log([r["vertices"] for r in rows])
    y = numpy.log([r["seconds"] for r in rows])
    exponent = float(numpy.polyfit(x, y, 1)[0])
    largest = rows[-1]["seconds"]
    met = largest < TARGET_SECONDS and exponent < TARGET_EXPONENT
    print(f"bench: rest faces grow as n^{exponent:.2f} over {SIZES[0]}..{SIZES[-1]} vertices (target below "
          f"{TARGET_EXPONENT}); {SIZES[-1]} vertices in {largest:.2f} s (target under {TARGET_SECONDS} s): "
          f"{'met' if met else 'MISSED'}")
    with open(out + ".tmp", "w", encoding="utf-8") as f:
        json.dump({"rows": rows, "exponent": exponent, "target_seconds": TARGET_SECONDS,
                   "target_exponent": TARGET_EXPONENT, "met": met}, f, indent=1)
    os.replace(out + ".tmp", out)
    return 0 if met else 1


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1].strip())
    sys.exit(main(sys.argv[1], sys.argv[2]))
