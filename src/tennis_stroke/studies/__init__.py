"""Speed against accuracy: work-precision, stability, the model ladder and the cost of
the optimum search.  May use the experiments; nothing below imports from here.
"""
