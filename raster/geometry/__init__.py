"""raster's geometry kernel (being gathered here from the top-level modules).

=====================  ==============================================
module                 contents
=====================  ==============================================
``patches``            tensor-product Bezier patches of any degree and
                       bilinearly blended Coons patches: vectorized
                       evaluation with partial derivatives, subdivision,
                       linearization error bounds
=====================  ==============================================
"""
