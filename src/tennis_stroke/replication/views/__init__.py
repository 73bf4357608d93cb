"""The report's interactive views: Bokeh standalone documents, drawn from the result files
the static figures are drawn from (never re-simulating), embedded in the page with every
script inline (works from ``file://`` with the network off).  One module per family:

* :mod:`.maps`: a figure's map or curve, the paper's and our values of its claims marked;
* :mod:`.comparison`: a figure under the paper's configuration beside a scenario's, with
  their difference;
* :mod:`.strokes`: the strokes of a file animated in the plane;
* :mod:`.multiverse`: every consistent reading and every claim under it;
* :mod:`.tables` (sortable tables) and :mod:`.page` (the views of a page in one document).

Each view's data source has a ``name`` (``<figure>-map``, ``<figure>-now``,
``multiverse-claims``) through which the browser tests read it.
"""
