"""Stability where methods fail: the isolated contact over k for each method."""

import numpy as np

from tennis_stroke.pipeline.jobs import Timer, logged, save
from tennis_stroke.studies.stability import stability_map

p = snakemake.params
s = p.stability
with logged(snakemake.log[0]):
    clock = Timer()
    k = np.logspace(s["k_contact"]["start"], s["k_contact"]["stop"], s["k_contact"]["num"])
    ds = stability_map([(str(m), float(v)) for m, v in s["cases"]], k)
    save(ds, snakemake.output[0], p, clock())
