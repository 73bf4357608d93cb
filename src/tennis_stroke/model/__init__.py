"""The model: parameters and readings of the paper, and the equations of motion.

The one home of the physics; imports nothing else of the package.
"""
