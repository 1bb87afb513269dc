"""Safety limits.  Inputs beyond these raise :class:`raster.errors.LimitError`
(or :class:`raster.errors.CanvasError` for sizes) instead of exhausting memory
or time."""

#: Largest pixel buffer (width * height) a canvas may have: 10^8 pixels is
#: 1.6 GB of float32 RGBA.
MAX_PIXELS = 100_000_000

#: Largest canvas side in pixels.
MAX_SIDE = 100_000

#: Absolute coordinate magnitude beyond which geometry is refused (device px).
MAX_COORD = 1e9

#: Most line segments a single flatten call may produce.
MAX_FLATTEN_POINTS = 50_000_000

#: Deepest nesting of ``use`` instantiations the SVG tree builder follows.
MAX_USE_DEPTH = 64

#: Most nodes the SVG tree builder creates for one document (``use`` bombs):
#: building costs tens of microseconds a node, so this bounds a hostile
#: document to seconds.  The largest corpus document has about 6,600.
#: ``build_tree(max_elements=...)`` raises it for a trusted huge document.
MAX_ELEMENTS = 100_000
