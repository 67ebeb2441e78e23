"""Fixed-axes eigenvalues of a rigid rotor on supports that differ by direction
(tests/rotor_campbell_views.rs), written independently of autobal's equations.

Coordinates: the centre of mass's translation (x, y) and the slopes (a, b) = (dx/dz, dy/dz) of
the spin axis. A support at z (from the centre of mass) with stiffness (k_x, k_y) and damping
(c_x, c_y) acts on the displacement (x + z a, y + z b). Kinetic energy
m (x'^2 + y'^2)/2 + A (a'^2 + b'^2)/2 and the gyroscopic coupling of the polar moment C at the
spin W: A a'' + C W b' = moment about y, A b'' - C W a' = moment about x (the eigenvalues do not
depend on the sign of this coupling: mirroring y maps W to -W and keeps diagonal supports).

Reads JSON on stdin: {"m", "a", "c", "supports": [{"z", "kx", "ky", "cx", "cy"}], "omegas"}.
Writes {"eigenvalues": [[[re, im], ...] per speed]} of the state matrix
[[0, I], [-M^-1 K, -M^-1 (D + W G)]] by numpy.linalg.eigvals.
"""
import json
import sys

import numpy as np


def main():
    req = json.load(sys.stdin)
    m, a, c = req["m"], req["a"], req["c"]
    K = np.zeros((4, 4))
    D = np.zeros((4, 4))
    # q = (x, a, y, b): the x plane (x, a) and the y plane (y, b)
    for s in req["supports"]:
        z = s["z"]
        u = np.array([1.0, z])
        for (i, j), k, d in (((0, 1), s["kx"], s["cx"]), ((2, 3), s["ky"], s["cy"])):
            K[np.ix_([i, j], [i, j])] += k * np.outer(u, u)
            D[np.ix_([i, j], [i, j])] += d * np.outer(u, u)
    M = np.diag([m, a, m, a])
    G = np.zeros((4, 4))
    G[1, 3] = c
    G[3, 1] = -c
    out = []
    for w in req["omegas"]:
        Minv = np.linalg.inv(M)
        A = np.block([[np.zeros((4, 4)), np.eye(4)], [-Minv @ K, -Minv @ (D + w * G)]])
        ev = np.linalg.eigvals(A)
        out.append([[float(z.real), float(z.imag)] for z in ev])
    json.dump({"eigenvalues": out}, sys.stdout)


main()
