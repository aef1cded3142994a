#!/usr/bin/env python3
"""Writes a P3F/NFF scene as a POV-Ray 3.7 scene, to measure both renderers
on the same geometry (docs/PERFORMANCE.md, "Against POV-Ray 3.7").

Covers what the bundled comparison scenes use: the camera (right-handed, as
the workbench's image right is (at - from) x up), `bclr`/`b`, point lights,
materials (`f`, NFF or P3F), spheres, polygons, boxes and cones. Whitted
materials map to `ambient 0.1 diffuse Kd specular Ks reflection Ks`, glass
to `filter T` with its `ior`. Anything else is an error, not a silent
omission.

    python3 scripts/p3f_to_pov.py scenes/balls_medium.p3f > balls_medium.pov
"""

import math
import sys

COMMANDS = {
    "v", "from", "at", "up", "angle", "hither", "resolution", "aperture", "focal",
    "b", "bclr", "l", "f", "s", "p", "box", "c", "accel", "spp",
}


def tokens(text):
    for line in text.splitlines():
        for word in line.split():
            if word.startswith("#"):
                break
            yield word


def number(word):
    return float(word)


def vec(words):
    x, y, z = (number(w) for w in words)
    return f"<{x!r}, {y!r}, {z!r}>"


def convert(text):
    words = list(tokens(text))
    out = []
    camera = {"up": "<0, 1, 0>", "angle": 45.0, "resolution": (512, 512)}
    material = None
    i = 0

    def take(n):
        nonlocal i
        part = words[i : i + n]
        if len(part) < n:
            raise SystemExit(f"unexpected end of file after {words[i - 1]!r}")
        i += n
        return part

    def numbers_until_command():
        count = 0
        while i + count < len(words) and words[i + count] not in COMMANDS:
            count += 1
        return count

    while i < len(words):
        word = words[i]
        i += 1
        if word == "v":
            pass
        elif word in ("accel", "spp", "hither", "focal"):
            take(1)
        elif word == "aperture":
            if number(take(1)[0]) > 0:
                raise SystemExit("a lens (aperture > 0) is not converted")
        elif word in ("from", "at", "up"):
            camera[word] = vec(take(3))
        elif word == "angle":
            camera["angle"] = number(take(1)[0])
        elif word == "resolution":
            w, h = take(2)
            camera["resolution"] = (int(w), int(h))
        elif word in ("b", "bclr"):
            out.append(f"background {{ rgb {vec(take(3))} }}")
        elif word == "l":
            position = vec(take(3))
            colour = vec(take(3)) if numbers_until_command() >= 3 else "<1, 1, 1>"
            out.append(f"light_source {{ {position} color rgb {colour} }}")
        elif word == "f":
            values = [number(w) for w in take(numbers_until_command())]
            if len(values) == 8:
                r, g, b, kd, ks, shine, t, ior = values
            elif len(values) == 11:
                r, g, b, kd, _, _, _, ks, shine, t, ior = values
            else:
                raise SystemExit(f"material with {len(values)} numbers")
            roughness = min(1.0, 1.0 / max(shine, 1.0))
            interior = f" interior {{ ior {ior!r} }}" if t > 0 and ior > 0 else ""
            material = (
                f"texture {{ pigment {{ rgbf <{r!r}, {g!r}, {b!r}, {t!r}> }} "
                f"finish {{ ambient 0.1 diffuse {kd!r} specular {ks!r} "
                f"roughness {roughness!r} reflection {ks!r} }} }}{interior}"
            )
        elif word == "s":
            cx, cy, cz, r = take(4)
            out.append(f"sphere {{ {vec((cx, cy, cz))}, {number(r)!r} {material} }}")
        elif word == "p":
            n = int(take(1)[0])
            points = [vec(take(3)) for _ in range(n)]
            points.append(points[0])
            out.append(f"polygon {{ {n + 1}, {', '.join(points)} {material} }}")
        elif word == "box":
            values = take(6)
            out.append(f"box {{ {vec(values[:3])}, {vec(values[3:])} {material} }}")
        elif word == "c":
            bx, by, bz, br, ax, ay, az, ar = take(8)
            out.append(
                f"cone {{ {vec((bx, by, bz))}, {number(br)!r}, {vec((ax, ay, az))}, "
                f"{number(ar)!r} open {material} }}"
            )
        else:
            raise SystemExit(f"unsupported command {word!r}")

    width, height = camera["resolution"]
    aspect = width / height
    # The workbench's angle is vertical; POV-Ray's is horizontal.
    horizontal = 2 * math.degrees(math.atan(math.tan(math.radians(camera["angle"] / 2)) * aspect))
    head = [
        "#version 3.7;",
        "global_settings { assumed_gamma 1.0 max_trace_level 5 }",
        f"camera {{ location {camera['from']} sky {camera['up']} up y "
        f"right -x*{aspect!r} angle {horizontal!r} look_at {camera['at']} }}",
    ]
    return "\n".join(head + out) + "\n"


if __name__ == "__main__":
    with open(sys.argv[1]) as scene:
        sys.stdout.write(convert(scene.read()))
