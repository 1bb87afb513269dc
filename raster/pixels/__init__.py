"""The pixel layer: scan conversion (:mod:`.scan`, exact-area coverage of
edges), the premultiplied float32 canvas (:mod:`.canvas`), compositing and
blend modes (:mod:`.compositing`), canvas views (:mod:`.views`), hairline
outlines (:mod:`.hairline`), filter-effect operations (:mod:`.effects`), mesh
gradient colours (:mod:`.mesh`), PNG encoding (:mod:`.png`) and the output
formats (:mod:`.encode`: PNG, JPEG, WebP, TIFF, BMP).  It knows
nothing of SVG or of the tree: arrays, masks and the geometry kernel only."""
