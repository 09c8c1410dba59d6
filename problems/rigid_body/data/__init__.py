"""Data files shipped with the package (read with :mod:`importlib.resources`).

``table1.csv``
    Table 1 of the seed paper, copied verbatim (the entries keep their printed form, e.g.
    ``2.79E-01``, because the printed precision sets the tolerance of the reproduction).
"""
