"""The paper's experiments as functions of plain parameters, and the identification of
the paper's unstated readings.  Imports the solver and the model, never a layer above.
"""
