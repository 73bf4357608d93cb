"""The live explorer (``tennis-stroke explore``): a local Bokeh server that recomputes the
map of Figs. 2-3, the curve of Fig. 9, a picked stroke and the claims they test at the
settings a reader picks (:mod:`tennis_stroke.live.app`, :mod:`tennis_stroke.live.server`)."""
