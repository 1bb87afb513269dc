"""raster's pixel layer (being gathered here): scan conversion, canvas,
compositing, encoding.

=====================  ==============================================
module                 contents
=====================  ==============================================
``mesh``               SVG 2 mesh gradients: colours of Coons-patch
                       meshes at pixel centres
=====================  ==============================================
"""
