"""Importing this module registers raster's SVG plugin with Pillow
(:func:`raster.pillow.register` with its defaults)::

    import raster.pillow.auto  # noqa: F401
    from PIL import Image
    Image.open('drawing.svg')
"""

from . import register

register()
