"""One map from its chunks; fails when its share of failed strokes is above the limit.
A map of the table of experiments gets its labels from the units table again."""

from tennis_stroke.io.interrupts import quiet_job_stops

quiet_job_stops()  # from here on a signal ends the job in one line, also while importing

from tennis_stroke.io.failures import check_failure_share
from tennis_stroke.io.netcdf import relabelled, write_netcdf
from tennis_stroke.pipeline.chunks import gather_chunks
from tennis_stroke.pipeline.jobs import logged

with logged(snakemake.log[0]):
    ds = gather_chunks(snakemake.input.chunks)
    if snakemake.params.relabel:
        ds = relabelled(ds)
    counts = check_failure_share(ds, snakemake.params.max_failure_share, snakemake.output[0])
    print(f"gathered {len(snakemake.input.chunks)} chunks; strokes: {counts}")
    write_netcdf(ds, snakemake.output[0])
