#!/usr/bin/python3
"""Write the meshes of the shipped bodies of one's own, each in another format a user has:
housner-block.off (Housner's rectangular block, 2b x 2d x 2h with b = 0.1 m, d = 0.15 m, h = 0.4 m),
die.obj (a cube of side 16 mm, a die without its pips' hollows and rounded edges), coin.stl (a coin as a
right prism over a regular 64-gon: radius 12.5 mm, thickness 2 mm; ASCII STL). Run from this folder:
the files are committed, this script says where their numbers come from."""
import math


def box(a, b, c):
    v = [(x, y, z) for z in (-c, c) for y in (-b, b) for x in (-a, a)]
    # quads counter-clockwise seen from outside
    f = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return v, f


def write_off(path, v, f, comment):
    with open(path, "w") as out:
        out.write("OFF\n# %s\n%d %d 0\n" % (comment, len(v), len(f)))
        for p in v:
            out.write("%.17g %.17g %.17g\n" % p)
        for q in f:
            out.write("%d %s\n" % (len(q), " ".join(str(i) for i in q)))


def write_obj(path, v, f, comment):
    with open(path, "w") as out:
        out.write("# %s\n" % comment)
        for p in v:
            out.write("v %.17g %.17g %.17g\n" % p)
        for q in f:
            out.write("f %s\n" % " ".join(str(i + 1) for i in q))


def write_stl(path, v, tris, name):
    with open(path, "w") as out:
        out.write("solid %s\n" % name)
        for t in tris:
            a, b, c = (v[i] for i in t)
            u = [b[k] - a[k] for k in range(3)]
            w = [c[k] - a[k] for k in range(3)]
            n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
            s = math.sqrt(sum(x * x for x in n))
            out.write("  facet normal %.17g %.17g %.17g\n    outer loop\n" % tuple(x / s for x in n))
            for p in (a, b, c):
                out.write("      vertex %.17g %.17g %.17g\n" % p)
            out.write("    endloop\n  endfacet\n")
        out.write("endsolid %s\n" % name)


v, f = box(0.1, 0.15, 0.4)
write_off("housner-block.off", v, f, "Housner's block: 2b x 2d x 2h = 0.2 x 0.3 x 0.8 m, centred")
v, f = box(0.008, 0.008, 0.008)
write_obj("die.obj", v, f, "a die: a cube of side 16 mm, centred")
n, R, T = 64, 0.0125, 0.001
v = [(R * math.cos(2 * math.pi * k / n), R * math.sin(2 * math.pi * k / n), z) for z in (-T, T) for k in range(n)]
tris = []
for k in range(n):
    j = (k + 1) % n
    tris += [(k, j, n + j), (k, n + j, n + k)]          # the rim
for k in range(1, n - 1):
    tris += [(0, k + 1, k), (n, n + k, n + k + 1)]      # the faces: bottom turned down, top up
write_stl("coin.stl", v, tris, "coin")
