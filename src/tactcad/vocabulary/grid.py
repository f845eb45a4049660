"""The columns of a sensor's grid: how many a design may have, for every product, and for a
stacked array, whose rows pair each reference with elements of its own that measure. One
place, read by the design's validation, ``design --columns`` and the parts that name a
remedy (the bracket's bolt)."""

from __future__ import annotations

#: Most columns of a grid: the one range of ``array.columns`` and of ``design --columns``
#: (an element count the closed form and the drawings have been checked over).
MAX_COLUMNS = 12
#: The allowed range of the columns of a grid (inclusive), wherever they are asked: a comb,
#: paired across its rows, reads with one column.
COLUMNS_RANGE = (1, MAX_COLUMNS)
#: Fewest columns of a stacked array: each row pairs its reference with an element of its
#: own that measures.
MIN_PAIRED_COLUMNS = 2
#: The allowed range of a stacked array's columns (inclusive): the one range of its design
#: file's ``array.columns`` (:func:`tactcad.design.array_plan.stacked_columns_error`, judged where a design file is
#: loaded; a plan built for one element's figures may have one column) and of
#: ``design --columns``.
STACKED_COLUMNS_RANGE = (MIN_PAIRED_COLUMNS, MAX_COLUMNS)
#: Why a stacked array's columns are what they are (the grid's range, and a pair per row).
STACKED_COLUMNS_WHY = ("each row pairs its reference with the row's other elements, so a row "
                       "of one column has no element left to measure; the most is the grid's "
                       "(array.columns)")
