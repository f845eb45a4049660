"""The vocabulary every design file and part module is written in (no CAD kernel):

* :mod:`tactcad.vocabulary.schema`: the one schema mechanism of the design files
  (pydantic sections, every refusal at once as ``file: field = value: allowed ...``),
  reading TOML, the content hash, the ``[assumptions]`` table, derived values with
  their reasons;
* :mod:`tactcad.vocabulary.standards`: ISO bolts and nuts, ISO 15 bearings, stock lengths;
* :mod:`tactcad.vocabulary.material_library`: the materials library;
* :mod:`tactcad.vocabulary.process`: the typed process of a part (:class:`Method`).
"""
