"""Fabrication drawings: A3 sheets (:mod:`.sheet`) of orthographic views
projected from the part's solid (:mod:`.views`), dimensioned from the plan
(:mod:`.compose`), and all sheets in one PDF (:mod:`.pdf`). The export run
writes them (:mod:`tactcad.export.jobs`): ``drawings/<part>.svg``,
``drawings/drawings.pdf`` and the first element's sheet as PNG.
"""
