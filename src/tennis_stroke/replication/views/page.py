"""The views a page embeds, in one Bokeh document: BokehJS inline (only the parts the
views use) and one script for all of them, so the page works from ``file://`` with the
network off."""

from __future__ import annotations

from collections.abc import Mapping

from bokeh.document import Document
from bokeh.embed import components
from bokeh.resources import Resources

#: BokehJS inline, only the parts the views use (no WebGL, no MathJax: 1.9 of 3.9 MB).
RESOURCES = Resources(mode="inline", components=["bokeh", "bokeh-widgets", "bokeh-tables"])


def page_views(views: Mapping[str, object]) -> tuple[str, dict[str, str]]:
    """Bokeh's inline resources with the one script of all ``views`` (one document), and
    each view's div by name: what the page embeds.  The views go into one document in
    one step: Bokeh walks a document's models again after each root it adds, so adding
    them one by one (what ``components`` does with views of no document) walks them
    once per view."""
    document = Document()
    with document.models.freeze():
        for view in views.values():
            document.add_root(view)
    script, divs = components(dict(views))
    return RESOURCES.render() + script, divs
