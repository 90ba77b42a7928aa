#!/usr/bin/env python3
"""Where does a face-up moissanite's table send the light of its two modes?

An independent back-of-envelope check for the moissanite comparison (README.md): the camera
ray through the table near its centre goes down near the optic axis (c = +Y, so both modes
see n_o), reflects off the pavilion main facing +X, crosses the stone, reflects off the
opposite pavilion main and leaves through the table. At each internal reflection the
tangential wave vector n * k_t is conserved (Born & Wolf 15.3); the reflected ordinary wave
has n_o, the reflected extraordinary wave n(theta), 1/n^2 = cos^2/n_o^2 + sin^2/n_e^2 with
theta its angle to c. In this plane of incidence (it contains c) s-light stays ordinary and
p-light stays extraordinary, so the two paths that carry the light are ooo and eee.

If a renderer reflects every mode as a mirror (wave normal k - 2 (k.n) n, whatever the
mode), the leg after the reflection keeps the ordinary direction and both modes exit at the
`ooo` angle: no doubling of what the table shows. Pure Python, no dependencies.
"""

import math

N_O, N_E = 2.648, 2.690  # moissanite at 589 nm (Wang et al. 2013, both renderers' tables)
PAVILION = math.radians(40.75)  # Iris's Tolkowsky pavilion angle
C = (0.0, 1.0, 0.0)


def add(a, b, s=1.0):
    return tuple(x + s * y for x, y in zip(a, b))


def mul(a, s):
    return tuple(x * s for x in a)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def unit(a):
    return mul(a, 1.0 / math.sqrt(dot(a, a)))


def index(u, mode):
    if mode == "o":
        return N_O
    ct = dot(u, C)
    return 1.0 / math.sqrt(ct * ct / N_O**2 + (1.0 - ct * ct) / N_E**2)


def wave_normal(tangent, normal, kt, mode):
    """Unit wave normal sin(a) tangent + cos(a) normal with index(u) sin(a) = kt."""
    lo, hi = 0.0, math.pi / 2
    for _ in range(80):
        a = 0.5 * (lo + hi)
        u = add(mul(tangent, math.sin(a)), normal, math.cos(a))
        if index(u, mode) * math.sin(a) > kt:
            hi = a
        else:
            lo = a
    return unit(add(mul(tangent, math.sin(a)), normal, math.cos(a)))


def split(u, n, facet):
    """Tangential k (unit direction, length) of wave normal u with index n at a facet."""
    k = mul(u, n)
    kt = add(k, facet, -dot(k, facet))
    length = math.sqrt(dot(kt, kt))
    return (mul(kt, 1.0 / length) if length > 0 else (0.0, 0.0, 0.0)), length


def reflect(u, n, facet, mode):
    tangent, kt = split(u, n, facet)
    r = wave_normal(tangent, mul(facet, -1.0), kt, mode)  # back into the stone
    return r, index(r, mode)


def leave(u, n, facet):
    tangent, kt = split(u, n, facet)
    if kt >= 1.0:
        return None
    return unit(add(mul(tangent, kt), facet, math.sqrt(1.0 - kt * kt)))


def main():
    p1 = (math.sin(PAVILION), -math.cos(PAVILION), 0.0)
    p2 = (-math.sin(PAVILION), -math.cos(PAVILION), 0.0)
    table = (0.0, 1.0, 0.0)
    print(f"n_o {N_O}, n_e {N_E}, pavilion {math.degrees(PAVILION)} deg, optic axis +Y")
    print("camera ray tilt | path: exit angle from the zenith (deg)")
    for tilt in (0.3, 2.0, 5.0):
        t = math.radians(tilt)
        d = unit((math.sin(t), -math.cos(t), 0.0))
        row = []
        for modes in ("ooo", "eee", "oeo", "oee"):
            tangent, kt = split(d, 1.0, table)
            u = wave_normal(tangent, (0.0, -1.0, 0.0), kt, modes[0])
            n = index(u, modes[0])
            u, n = reflect(u, n, p1, modes[1])
            u, n = reflect(u, n, p2, modes[2])
            out = leave(u, n, table)
            row.append(f"{modes} {math.degrees(math.acos(out[1])):6.2f}" if out else f"{modes} TIR")
        # Mirror reflections whatever the mode (the mode only picks the index):
        tangent, kt = split(d, 1.0, table)
        u = wave_normal(tangent, (0.0, -1.0, 0.0), kt, "e")
        for facet in (p1, p2):
            u = unit(add(u, facet, -2.0 * dot(u, facet)))
        out = leave(u, index(u, "e"), table)
        row.append(f"eee mirrored {math.degrees(math.acos(out[1])):6.2f}")
        print(f"{tilt:5.1f} deg | " + " | ".join(row))


if __name__ == "__main__":
    main()
