"""The pixel layer: scan conversion (:mod:`.scan`, exact-area coverage of
edges), the premultiplied float32 canvas (:mod:`.canvas`), compositing and
blend modes (:mod:`.compositing`), canvas views (:mod:`.views`), hairline
outlines (:mod:`.hairline`), filter-effect operations (:mod:`.effects`), mesh
gradient colours (:mod:`.mesh`) and PNG encoding (:mod:`.png`).  It knows
nothing of SVG or of the tree: arrays, masks and the geometry kernel only."""
