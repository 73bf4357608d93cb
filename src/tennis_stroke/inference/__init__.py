"""Inference: the paper's unstated readings (the reading space), their identification
as a fit, the robustness analysis (the multiverse) and what each claim is and how it
is measured.  Imports the experiments and the layers below; the replication reads its
files.
"""
