"""Dense linear element (superelement) forces: f = −K (x − x₀) on listed DOFs.

Rows are summed in parallel, each by one thread, so the forces are the
same bit for bit on any number of threads. A row's sum may be reassociated
(``fastmath`` reassoc): the compiler then keeps several partial sums in
vector registers instead of one serial chain of additions, four times
faster at 642 DOF; the order is still fixed by the compiled code, not by
the threads. No other fast-math flag: NaN and infinity stay visible to the
loop's divergence check. (A BLAS matvec here would start its own thread
pool beside Numba's and slow both.)
"""

from numba import njit, prange

_REASSOC = {"reassoc", "contract"}


@njit(cache=True, parallel=True, fastmath=_REASSOC)
def matrix_forces(k, x, x0, nodes, comps, u, fe, f):
    """u = x[nodes, comps] − x0; fe = −K u (force on each DOF); f += fe.
    Returns the strain energy ½uᵀKu."""
    n = nodes.shape[0]
    for i in range(n):
        u[i] = x[nodes[i], comps[i]] - x0[i]
    for i in prange(n):
        s = 0.0
        for j in range(n):
            s += k[i, j] * u[j]
        fe[i] = -s
    e = 0.0
    for i in range(n):
        e -= 0.5 * u[i] * fe[i]
        f[nodes[i], comps[i]] += fe[i]
    return e


@njit(cache=True, parallel=True, fastmath=_REASSOC)
def matrix_kick(b, f, nodes, comps, fs, g, v, dt):
    """fs = f[nodes, comps]; g = B fs; v[nodes, comps] += dt g: the velocity
    correction of DOFs whose mass is a dense matrix (``consistent``). The
    forces are gathered once, so that the rows run over contiguous memory."""
    n = nodes.shape[0]
    for i in range(n):
        fs[i] = f[nodes[i], comps[i]]
    for i in prange(n):
        s = 0.0
        for j in range(n):
            s += b[i, j] * fs[j]
        g[i] = s
    for i in range(n):
        v[nodes[i], comps[i]] += dt * g[i]
