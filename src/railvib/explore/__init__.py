"""``railvib explore``: a local web page to vary a case and see its responses at once.

:mod:`railvib.explore.state` holds the controls, the case they make and what the page
draws of a run (no web library); :mod:`railvib.explore.app` serves the page with Bokeh
(the optional extra ``explore``, loaded only when the page is served;
docs/design/0007-live-explorer.md says why Bokeh).
"""

from railvib.explore.state import AS_CASE, Controls, Explorer, Frame, controls_from_values

__all__ = ["AS_CASE", "Controls", "Explorer", "Frame", "controls_from_values"]
