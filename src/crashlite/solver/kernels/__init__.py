"""Numba kernels of the explicit solver: arrays in, preallocated arrays out."""
