#!/usr/bin/env python3
"""Oblique near-plane clipping in Python for perspective matrices of the standard shape
(zeros outside M11, M13, M22, M23, M33, M34, M43), in every depth convention, with the adapter
that `oblique verify` drives: one JSON request per input line, one JSON answer per output line.

    oblique verify --impl 'python3 lengyel_perspective.py' \
        --families perspective,off_axis,infinite,y_flipped,jittered,x_flipped,xy_flipped,left_handed \
        --convention all
"""
import json
import math
import sys

# Depth range [z_low, z_high] of the clip volume, and the sign s in near = s M_3 + t M_4.
CONVENTIONS = {"gl": (-1.0, 1.0), "zero_one": (0.0, 1.0), "reversed_z": (0.0, 1.0)}


def sign(x):
    return (x > 0) - (x < 0)


def oblique_projection(m, c, convention):
    """Returns (status, 16 numbers or None) for M (row-major) and the camera-space plane C."""
    if not all(math.isfinite(v) for v in m + c):
        return "invalid_input", None
    A, B, D, E, G, H, K = m[0], m[2], m[5], m[6], m[10], m[11], m[14]
    shape = [i for i in range(16) if m[i] != 0 and i not in (0, 2, 5, 6, 10, 11, 14)]
    if shape or K == 0:
        return "invalid_input", None  # not the standard perspective shape
    if A == 0 or D == 0 or H == 0:
        return "singular_projection", None
    if not c[3] < 0:
        return "camera_not_behind_plane", None
    # a C does not depend on C's scale: bring C near 1 by a power of two (exact) first.
    e = math.frexp(max(abs(v) for v in c))[1]
    c = [math.ldexp(v, -e) for v in c]
    z_low, z_high = CONVENTIONS[convention]
    # Signs of C' = M^-T C: C'_x = C_x / A, C'_y = C_y / D, C'_z = C_w / H.
    sz = sign(c[3]) * sign(H)
    corner = (sign(c[0]) * sign(A), sign(c[1]) * sign(D),
              z_high if sz > 0 else z_low if sz < 0 else (z_low + z_high) / 2)
    # Q = M^-1 Q' for Q' = (corner, 1).
    q = ((corner[0] - B / K) / A, (corner[1] - E / K) / D, 1 / K, (corner[2] - G / K) / H)
    d = sum(ci * qi for ci, qi in zip(c, q))
    if not d > 0:
        return "plane_misses_view_volume", None
    a = (z_high - z_low) / d
    out = list(m)
    for j in range(4):
        ac, m4 = a * c[j], m[12 + j]
        out[8 + j] = {"gl": ac - m4, "zero_one": ac, "reversed_z": m4 - ac}[convention]
    if not all(math.isfinite(v) for v in out):
        return "out_of_range", None
    return "ok", out


# The adapter: numbers arrive as JSON numbers or as "nan", "inf", "-inf" (float() reads both).
for line in sys.stdin:
    request = json.loads(line)
    m = [float(x) for x in request["projection"]]
    c = [float(x) for x in request["plane"]]
    status, result = oblique_projection(m, c, request.get("convention", "gl"))
    answer = {"status": status, "projection": result} if result else {"status": status}
    print(json.dumps(answer), flush=True)
