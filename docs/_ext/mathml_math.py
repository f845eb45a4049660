"""Equations as MathML written when the site is built.

Sphinx's HTML pages typeset math with MathJax loaded from a CDN, so an
equation shows only with a network. This renderer converts each equation's
LaTeX to MathML with ``latex2mathml`` instead: browsers draw MathML natively
(MathML Core), the pages carry no script for it and open from ``file://``
offline. A displayed equation with a label keeps its number, as Sphinx
numbers it.
"""

from __future__ import annotations

from docutils import nodes
from latex2mathml.converter import convert


def mathml(latex: str, display: bool) -> str:
    """The MathML of one LaTeX equation (``display``: a block of its own)."""
    return convert(latex.strip(), display="block" if display else "inline")


def _visit_inline(self, node: nodes.Element) -> None:
    self.body.append(f'<span class="math">{mathml(node.astext(), display=False)}</span>')
    raise nodes.SkipNode


def _visit_block(self, node: nodes.Element) -> None:
    number = node.get("number")
    label = f'<span class="eqno">({number})</span>' if number else ""
    ids = f' id="{node["ids"][0]}"' if node.get("ids") else ""
    self.body.append(f'<div class="math mathml-block"{ids}>{label}'
                     f'{mathml(node.astext(), display=True)}</div>\n')
    raise nodes.SkipNode


def setup(app):
    app.add_html_math_renderer("mathml", (_visit_inline, None), (_visit_block, None))
    return {"parallel_read_safe": True, "parallel_write_safe": True}
