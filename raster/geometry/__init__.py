"""raster's geometry kernel: paths, Bezier maths, flattening, stroking and
exact bounds, beside the SVG layers (parser, tree, renderer, pixels) and
under the curve toolkit (:mod:`raster.curves`).

=====================  ====================================================
module                 contents
=====================  ====================================================
``transform``          :class:`Affine` (SVG matrix ``a b c d e f``)
``roots``              real roots of quadratics, cubics and of polynomials
                       of any degree on (0, 1)
``bezier``             Bernstein bases, de Casteljau, subdivision,
                       derivatives, power basis, degree elevation, extrema
                       and exact bounds of Bezier segments of any degree
``path``               :class:`Path` (verbs and points), :class:`Segments`
``pens``               the pen protocol: :class:`BasePen`,
                       :class:`PathBuilder`, :class:`TransformPen`,
                       :class:`RecordingPen`, :class:`BoundsPen`
``rules``              :class:`FillRule` (and the str enum base)
``pathdata``           SVG path data, arcs and basic shapes to paths
``flattening``         adaptive flattening within a tolerance
``bounds``             exact bounding boxes of paths
``stroking``           stroke outlines (joins, caps, dashes),
                       :class:`StrokeStyle`, :class:`LineJoin`,
                       :class:`LineCap`
``culling``            paths cut down to the segments that reach a box
                       (windows, strips, tiles): same fill, same stroke
``hull``               convex hull (monotone chain)
``patches``            tensor-product Bezier and Coons patches: evaluation,
                       partial derivatives, subdivision, error bounds
=====================  ====================================================

The kernel imports nothing from the SVG layers or the curve toolkit, and
this package imports none of its modules (``import raster.geometry.bezier``
loads only what that module needs).  The front-door names
(``raster.Path``, ``raster.flatten``, ``raster.bbox``, ``raster.stroke``,
...) are re-exported by :mod:`raster`.
"""
