#!/usr/bin/env python3
"""Reference lengths of a heavily weighted cubic NURBS (tests/test_length.cpp,
LengthGaussKronrod.HeavilyWeightedNurbs): knots (0,0,0,0,0.3,0.6,1,1,1,1), points (0,0) (10,5)
(20,-5) (30,10) (40,0) (50,3), weights (1, w, 1, 1/w, w, 1). Exact Cox-de Boor at 50 digits,
the speed by mpmath's numerical derivative, mpmath quad on 200 sub-intervals.
Needs only mpmath:  python3 tools/reference_weighted_nurbs.py   (about a minute)
Printed (generated 2026-11-22):
  w = 1e4: 52.034912281094772425
  w = 1e6: 52.03446296503609302
"""
import mpmath as mp

mp.mp.dps = 50


def basis(U, p, i, u):
    if p == 0:
        return mp.mpf(1) if U[i] <= u < U[i + 1] else mp.mpf(0)
    a = b = mp.mpf(0)
    if U[i + p] != U[i]:
        a = (u - U[i]) / (U[i + p] - U[i]) * basis(U, p - 1, i, u)
    if U[i + p + 1] != U[i + 1]:
        b = (U[i + p + 1] - u) / (U[i + p + 1] - U[i + 1]) * basis(U, p - 1, i + 1, u)
    return a + b


def length(w):
    U = [mp.mpf(x) for x in [0, 0, 0, 0, '0.3', '0.6', 1, 1, 1, 1]]
    P = [(0, 0), (10, 5), (20, -5), (30, 10), (40, 0), (50, 3)]
    W = [1, w, 1, 1 / w, w, 1]

    def C(u):
        N = [basis(U, 3, i, u) for i in range(6)]
        den = sum(N[i] * W[i] for i in range(6))
        return [sum(N[i] * W[i] * P[i][k] for i in range(6)) / den for k in range(2)]

    def speed(u):
        d = [mp.diff(lambda t: C(t)[k], u) for k in range(2)]
        return mp.sqrt(d[0] ** 2 + d[1] ** 2)

    pts = sorted(set([mp.mpf(0), mp.mpf(1)] + [mp.mpf(k) / 200 for k in range(1, 200)] + [mp.mpf('0.3'), mp.mpf('0.6')]))
    return mp.quad(speed, pts)


if __name__ == "__main__":
    for w in (mp.mpf(10) ** 4, mp.mpf(10) ** 6):
        print("w = %s: %s" % (mp.nstr(w, 3), mp.nstr(length(w), 20)))
