"""Linear solver for ICE's implicit pressure: PCG as an iterated sub-graph (framework Loop).

The operator is a symmetric 7-point stencil stored per cell (CC, 7 components:
mass term, then the coefficients of the W, E, S, N, B, T faces); `kernels.py` holds
the per-patch numba loops, `mg.py` the multigrid hierarchy of the coarse levels and
`pcg.py` the Loop body (conjugate gradients with a Jacobi or a geometric multigrid
preconditioner).
"""
