#!/usr/bin/env python3
"""Writes the generated scenes of the scale figures (issue 15) as steadyray TOML on stdout.

    many_objects.py spheres N             N spheres in a fixed 20 m x 20 m field, the view
                                          and lights of the built-in `spheres` scene
    many_objects.py instances N           N copies of a small mesh, spinning as one swarm,
                                          so that every frame moves every copy
    many_objects.py bunnies N MESH        N copies of the mesh file MESH (the Stanford bunny),
                                          MESH written as given: relative to where the scene
                                          file is saved

Only the Python standard library is needed (no requirements file). The output is
deterministic: the same arguments give the same file.
"""

import math
import random
import sys

HEAD = """name = "{name}"
background = [0.35, 0.45, 0.6]
ambient = 0.05

[camera]
eye = [0.0, 4.5, 10.0]
target = [0.0, 0.5, 0.0]
up = [0.0, 1.0, 0.0]
vfov_deg = 50.0

[path]
type = "orbit"
center = [0.0, 0.5, 0.0]
radius = 10.0
height = 4.0
frames = 360

[[materials]]
name = "ground"
type = "diffuse"
albedo = 0.7
checker = {{ size = 1.0, albedo_b = 0.3 }}

[[materials]]
name = "red"
type = "diffuse"
albedo = [0.8, 0.15, 0.1]

[[materials]]
name = "blue"
type = "diffuse"
albedo = [0.15, 0.3, 0.85]

[[materials]]
name = "white"
type = "diffuse"
albedo = 0.8

[[materials]]
name = "mirror"
type = "mirror"
reflectance = 0.9

[[materials]]
name = "glass"
type = "dielectric"
ior = 1.5

[[shapes]]
name = "ground"
type = "plane"
material = "ground"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
"""

LIGHTS = """
[[lights]]
position = [-8.0, 9.0, -8.0]
intensity = 60.0

[[lights]]
position = [8.0, 9.0, 8.0]
intensity = 60.0
"""

# The materials of the spheres, in the built-in scene's proportions: mostly diffuse.
SPHERE_MATERIALS = ["red", "blue", "white", "red", "blue", "white", "mirror", "glass"]

# An octahedron of unit circumradius: a small mesh for swarms of copies.
OCTAHEDRON = """positions = [[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]
triangles = [[0, 2, 4], [4, 2, 1], [1, 2, 5], [5, 2, 0], [0, 4, 3], [4, 1, 3], [1, 5, 3], [5, 0, 3]]
"""


def number(x):
    return repr(float(round(x, 4)))


def vec(*xs):
    return "[" + ", ".join(number(x) for x in xs) + "]"


def spheres(n):
    """n spheres on a jittered grid over x, z in [-10, 10], resting on the ground."""
    rng = random.Random(15)
    side = math.ceil(math.sqrt(n))
    step = 20.0 / side
    out = [HEAD.format(name=f"spheres-{n}")]
    for i in range(n):
        gx, gz = i % side, i // side
        radius = step * rng.uniform(0.3, 0.42)
        x = -10.0 + (gx + 0.5) * step + rng.uniform(-0.05, 0.05) * step
        z = -10.0 + (gz + 0.5) * step + rng.uniform(-0.05, 0.05) * step
        out.append(
            f"\n[[shapes]]\nname = \"s{i}\"\ntype = \"sphere\"\n"
            f"material = \"{SPHERE_MATERIALS[i % len(SPHERE_MATERIALS)]}\"\n"
            f"center = {vec(x, radius, z)}\nradius = {number(radius)}\n"
        )
    out.append(LIGHTS)
    return "".join(out)


def copies(n, size):
    """n instance entries scattered over x, z in [-9, 9], y in [0.3, 3]."""
    rng = random.Random(16)
    lines = []
    for _ in range(n):
        t = vec(rng.uniform(-9, 9), rng.uniform(0.3, 3.0), rng.uniform(-9, 9))
        lines.append(
            f"  {{ translate = {t}, rotate_y_deg = {number(rng.uniform(0, 360))}, "
            f"scale = {number(size * rng.uniform(0.7, 1.3))} }},\n"
        )
    return "instances = [\n" + "".join(lines) + "]\n"


def instances(n):
    out = [HEAD.format(name=f"instances-{n}")]
    out.append(
        '\n[[shapes]]\nname = "swarm"\ntype = "mesh"\nmaterial = "red"\n'
        + OCTAHEDRON
        + copies(n, 1.5 / math.sqrt(n) * 3.0)
        + "\n[shapes.motion]\nspin_deg_per_s = 30.0\n"
    )
    out.append(LIGHTS)
    return "".join(out)


def bunnies(n, mesh):
    out = [HEAD.format(name=f"bunnies-{n}")]
    # The bunny is 0.154 m tall in its file; its copies are scaled to about 0.6 to 1.2 m.
    out.append(
        f'\n[[shapes]]\nname = "bunnies"\ntype = "mesh"\nmaterial = "white"\n'
        f'path = "{mesh}"\n' + copies(n, 6.0)
    )
    out.append(LIGHTS)
    return "".join(out)


def main(args):
    if len(args) >= 2 and args[0] in ("spheres", "instances") and args[1].isdigit():
        n = int(args[1])
        sys.stdout.write(spheres(n) if args[0] == "spheres" else instances(n))
    elif len(args) == 3 and args[0] == "bunnies" and args[1].isdigit():
        sys.stdout.write(bunnies(int(args[1]), args[2]))
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
