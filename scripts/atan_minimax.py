#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Coefficients of the double-precision arctangent of the weighted methods (AtanMinimaxDouble in
Filters/vtkTangentFrameKernels.h): atan(z) ~ z + z*x*Q(x), x = z^2, z in [0, tan(pi/8)], with Q the
polynomial of the given degree that minimizes the largest relative error of atan (Remez exchange
on a grid, in 60-digit decimal arithmetic; standard library only).

    python3 scripts/atan_minimax.py 9     # prints the error and the coefficients, Q(0) first
"""
import math
import sys
from decimal import Decimal, getcontext

getcontext().prec = 60
A = 3 - 2 * Decimal(2).sqrt()  # tan(pi/8)^2, the end of the x range


def atan(z):
    """atan(z) for |z| < 1/2 by its series, to 58 digits."""
    total, power, k, z2 = Decimal(0), z, 0, z * z
    while True:
        term = power / (2 * k + 1)
        if abs(term) < Decimal(10) ** -58:
            return total
        total += -term if k % 2 else term
        power *= z2
        k += 1


def target(x):
    """Q's ideal value at x and the weight that turns Q's error into atan's relative error."""
    z = x.sqrt()
    a = atan(z)
    return (a - z) / (z * x), z * x / a


def solve(m, b):
    """Gauss-Jordan elimination with partial pivoting."""
    n = len(b)
    rows = [r[:] + [v] for r, v in zip(m, b)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(rows[r][c]))
        rows[c], rows[p] = rows[p], rows[c]
        for r in range(n):
            if r != c:
                f = rows[r][c] / rows[c][c]
                rows[r] = [x - f * y for x, y in zip(rows[r], rows[c])]
    return [rows[r][n] / rows[r][r] for r in range(n)]


def horner(c, x):
    s = Decimal(0)
    for ck in reversed(c):
        s = s * x + ck
    return s


def fit(degree, grid=3000, iterations=12):
    n = degree + 2  # alternation points
    points = [A * (1 - Decimal(math.cos(math.pi * (i + 0.5) / n))) / 2 for i in range(n)]
    xs = [A * Decimal(i + 1) / grid for i in range(grid)]
    targets = [target(x) for x in xs]
    coefficients = []
    for _ in range(iterations):
        m, b = [], []
        for i, x in enumerate(points):
            q, w = target(x)
            m.append([w * x**k for k in range(degree + 1)] + [Decimal(-1) ** i])
            b.append(w * q)
        coefficients = solve(m, b)[: degree + 1]
        err = [w * (horner(coefficients, x) - q) for x, (q, w) in zip(xs, targets)]
        # The local extrema of |err|, then one per run of equal signs (the largest).
        extrema = [i for i in range(len(xs))
                   if abs(err[i]) >= abs(err[i - 1] if i > 0 else 0)
                   and abs(err[i]) >= abs(err[i + 1] if i + 1 < len(xs) else 0)]
        alternating = []
        for i in extrema:
            if alternating and (err[alternating[-1]] > 0) == (err[i] > 0):
                if abs(err[i]) > abs(err[alternating[-1]]):
                    alternating[-1] = i
            else:
                alternating.append(i)
        while len(alternating) > n:
            alternating.pop(0 if abs(err[alternating[0]]) < abs(err[alternating[-1]]) else -1)
        if len(alternating) < n:
            break
        points = [xs[i] for i in alternating]
    return coefficients


def relative_error(coefficients, samples=4000):
    """The largest relative error of atan with the coefficients as given (e.g. rounded)."""
    worst = Decimal(0)
    for i in range(samples):
        x = A * Decimal(i + 1) / samples
        q, w = target(x)
        worst = max(worst, abs(w * (horner(coefficients, x) - q)))
    return worst


if __name__ == "__main__":
    for degree in map(int, sys.argv[1:] or ["9"]):
        rounded = [Decimal(float(c)) for c in fit(degree)]
        print(f"degree {degree}: relative error {float(relative_error(rounded)):.3e} "
              "with the coefficients rounded to double")
        print("  " + ",\n  ".join(repr(float(c)) for c in rounded))
