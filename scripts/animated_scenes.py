#!/usr/bin/env python3
"""Writes the canonical animated scenes (scenes/*-orbit.toml, -walk, -moving; docs/design.md §10).

Deterministic: rerun after changing a base scene's placements. Each file derives from its still
scene (`[scene] base`) and adds an [animation] table (format: scenes/animation.h).
"""
import math
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parent.parent
SCENES = ROOT / "scenes"


def vec(v):
    return "[" + ", ".join(f"{x:.4f}" for x in v) + "]"


def toplight_orbit():
    # The light circles above the objects once in 4 s at toplight's height, aiming at the origin.
    lines = ["# toplight with its light circling above the objects: one turn in 4 s (radius 1.6 m at",
             "# the canonical height), Catmull-Rom through 13 keys. Written by scripts/animated_scenes.py.",
             "[scene]", 'base = "toplight"', 'name = "toplight-orbit"', "",
             "[animation]", "end = 4.0", "fps = 30", 'interpolation = "catmull-rom"', ""]
    for k in range(13):
        a = 2 * math.pi * k / 12
        lines += ["[[animation.light]]", f"time = {4.0 * k / 12:.6f}",
                  f"position = {vec((1.6 * math.cos(a), 7.0, 1.6 * math.sin(a)))}", ""]
    return "\n".join(lines)


def parallel_walk():
    # The camera walks 8 m down the corridor while the light's target sways left and right.
    lines = ["# parallel with the camera walking 8 m down the corridor while the light's target sways",
             "# 2 m left and right, 4 s. Written by scripts/animated_scenes.py.",
             "[scene]", 'base = "parallel"', 'name = "parallel-walk"', "",
             "[animation]", "end = 4.0", "fps = 30", 'interpolation = "catmull-rom"', ""]
    for k in range(5):
        t = float(k)
        z = 10.0 - 2.0 * k
        lines += ["[[animation.camera]]", f"time = {t:.1f}", f"position = {vec((0.0, 1.7, z))}",
                  f"target = {vec((0.0, 1.2, z - 20.0))}", ""]
    for k in range(9):
        t = 0.5 * k
        x = 2.0 * math.sin(math.pi * k / 4)
        lines += ["[[animation.light]]", f"time = {t:.1f}", f"target = {vec((x, 0.8, -14.0))}", ""]
    return "\n".join(lines)


def multiple_moving():
    # Every object of `multiple` moves: most circle about their place (radius 0.5-0.9 m, one or
    # two turns, either way round); four pairs of row neighbours swap places and back, passing
    # through each other's outer volumes half way.
    text = (SCENES / "multiple.toml").read_text()
    objects = []
    for block in text.split("[[objects]]")[1:]:
        name = re.search(r'^name = "([^"]+)"', block, re.M).group(1)
        translate = re.search(r"^translate = \[([^\]]+)\]", block, re.M)
        if name != "floor":
            objects.append((name, [float(x) for x in translate.group(1).split(",")]))
    assert len(objects) == 32, len(objects)
    lines = ["# multiple with its 32 objects on paths over 4 s: most circle about their places; four pairs",
             "# of row neighbours swap places and back, passing through each other's outer volumes.",
             "# Written by scripts/animated_scenes.py.",
             "[scene]", 'base = "multiple"', 'name = "multiple-moving"', "",
             "[animation]", "end = 4.0", "fps = 30", 'interpolation = "catmull-rom"', ""]
    swaps = {0: 1, 8: 9, 14: 15, 24: 25}
    partner = {**swaps, **{b: a for a, b in swaps.items()}}
    keys = 9
    for i, (name, p) in enumerate(objects):
        for k in range(keys):
            t = 4.0 * k / (keys - 1)
            if i in partner:
                q = objects[partner[i]][1]
                s = 0.5 - 0.5 * math.cos(2 * math.pi * t / 4.0)  # 0 -> 1 (at 2 s) -> 0
                pos = [p[j] + s * (q[j] - p[j]) for j in range(3)]
                pos[1] = p[1]
            else:
                r = 0.5 + 0.4 * ((i * 7) % 5) / 4
                turns = 1 + (i % 2)
                sign = 1 if i % 3 else -1
                a = sign * 2 * math.pi * turns * t / 4.0 + i
                pos = [p[0] + r * (math.cos(a) - math.cos(i)), p[1],
                       p[2] + r * (math.sin(a) - math.sin(i))]
            lines += ["[[animation.objects]]", f'name = "{name}"', f"time = {t:.1f}",
                      f"translate = {vec(pos)}", ""]
    return "\n".join(lines)


def engine_orbit():
    # The light circles above the engine once in 4 s at engine's height and radius, aiming at its
    # target: the shafts through the gaps between the parts turn under it.
    lines = ["# engine with its light circling above the assembly: one turn in 4 s (radius 1.5 m, 3.2 m",
             "# up, aimed at engine's target), Catmull-Rom through 13 keys. Every frame moves the light:",
             "# the beam tree, regions and boundary meshes over 115 parts' convex pieces are rebuilt.",
             "# Written by scripts/animated_scenes.py.",
             "[scene]", 'base = "engine"', 'name = "engine-orbit"', "",
             "# A light move rebuilds the tree every frame: the parts' volumes (a tree of ~80k nodes)",
             "# rather than engine's exact triangles (~200k nodes, three times the build).",
             "[beamtree]", 'occluders = "volumes"', "",
             "[animation]", "end = 4.0", "fps = 30", 'interpolation = "catmull-rom"', ""]
    for k in range(13):
        # Starts where engine's light stands (behind the engine, to the right).
        a = math.atan2(-1.4, 0.6) + 2 * math.pi * k / 12
        lines += ["[[animation.light]]", f"time = {4.0 * k / 12:.6f}",
                  f"position = {vec((1.5 * math.cos(a), 3.2, 1.5 * math.sin(a)))}", ""]
    return "\n".join(lines)


for name, make in [("toplight-orbit", toplight_orbit), ("parallel-walk", parallel_walk),
                   ("multiple-moving", multiple_moving), ("engine-orbit", engine_orbit)]:
    (SCENES / f"{name}.toml").write_text(make())
    print(f"wrote scenes/{name}.toml")
