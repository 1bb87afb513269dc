"""raster's geometry kernel: paths, Bezier maths, flattening, stroking and
exact bounds, beside the SVG layers (parser, tree, renderer, pixels) and
under the curve toolkit (:mod:`raster.curves`).

=====================  ====================================================
module                 contents
=====================  ====================================================
``transform``          :class:`Affine` (SVG matrix ``a b c d e f``)
``path``               :class:`Path` (verbs and points), :class:`Segments`,
                       the pens (:class:`PathBuilder`, ...)
``pathdata``           SVG path data, arcs and basic shapes to paths
``flattening``         adaptive flattening within a tolerance
``bounds``             exact bounding boxes of paths
``stroking``           stroke outlines (joins, caps, dashes)
``hull``               convex hull (monotone chain)
=====================  ====================================================

The kernel imports nothing from the SVG layers or the curve toolkit.  The
front-door names (``raster.Path``, ``raster.flatten``, ``raster.bbox``, ...)
are re-exported by :mod:`raster`.
"""
