"""The drawing functions of the registry's figures, one module each, named after its
function (:attr:`tennis_stroke.replication.registry.Figure.draw`), and their shared
helpers (:mod:`.axes`).  One module per function: a figure job's code inputs are its own
drawing module, so an edit of one drawing reruns only the figures it draws.

Matplotlib draws without a display (the Agg backend), set here before any drawing module
imports ``pyplot``.
"""

import matplotlib

matplotlib.use("Agg")
