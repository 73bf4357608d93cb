"""The paper's experiments as functions of plain parameters, their grids, and the
table of result files.  Imports the solver, the model and io, never a layer above.
"""
