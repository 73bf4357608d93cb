"""The numerics: generated Runge-Kutta kernels, the compiled phase integrator and stroke
driver, the result table, and the independent scipy path (``reference``).

Imports only :mod:`tennis_stroke.model`.
"""
