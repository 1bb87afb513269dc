"""The pixel layer: what happens to an image once it is pixels -- scan
conversion, the canvas and compositing, and encoding into files.  For now
it holds :mod:`raster.pixels.encode` (PNG, JPEG, WebP, TIFF and BMP
output); the scan converter, canvas and PNG encoder still live in
:mod:`raster.scan`, :mod:`raster.canvas` and :mod:`raster.png`."""
