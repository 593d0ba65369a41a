"""Numba kernels of the verification toolkit (numpy, numba, math only)."""

from numba import njit, prange


@njit(cache=True, parallel=True)
def biquad_filtfilt(x, a0, a1, a2, b1, b2, out):
    """Second-order recursive filter run forward, then backward, per column.

    x (n, m) float64: m signals sampled at one uniform step; out (n, m)
    float64, preallocated. The recursion is the SAE J211-1 one,
    y[i] = a0 x[i] + a1 x[i-1] + a2 x[i-2] + b1 y[i-1] + b2 y[i-2];
    each pass starts in the steady state of its first sample (the filter's
    DC gain is 1), so a constant signal passes through unchanged.
    Columns are independent, so any thread count gives the same bits.
    """
    n, m = x.shape
    for j in prange(m):
        x1 = x[0, j]
        x2 = x1
        y1 = x1
        y2 = x1
        for i in range(n):
            xi = x[i, j]
            yi = a0 * xi + a1 * x1 + a2 * x2 + b1 * y1 + b2 * y2
            x2 = x1
            x1 = xi
            y2 = y1
            y1 = yi
            out[i, j] = yi
        x1 = out[n - 1, j]
        x2 = x1
        y1 = x1
        y2 = x1
        for i in range(n - 1, -1, -1):
            xi = out[i, j]
            yi = a0 * xi + a1 * x1 + a2 * x2 + b1 * y1 + b2 * y2
            x2 = x1
            x1 = xi
            y2 = y1
            y1 = yi
            out[i, j] = yi
