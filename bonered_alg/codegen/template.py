"""Module text from templates rendered strictly (an undefined name is an error).

The templates live in ``codegen/templates``; the filters write Python literals
deterministically (``repr`` of strings and tuples, floats with ``repr``).
"""

from __future__ import annotations

from functools import lru_cache

import jinja2


def _pyfloat(value) -> str:
    return "None" if value is None else repr(float(value))


def _pytuple(values) -> str:
    return repr(tuple(values))


@lru_cache(maxsize=1)
def _environment() -> jinja2.Environment:
    env = jinja2.Environment(
        loader=jinja2.PackageLoader("bonered_alg.codegen", "templates"),
        undefined=jinja2.StrictUndefined, keep_trailing_newline=True, autoescape=False)
    env.filters.update(pyrepr=repr, pyfloat=_pyfloat, pytuple=_pytuple)
    return env


def render(template: str, context: dict) -> str:
    """Render ``template`` with ``context``; an undefined name raises ``UndefinedError``."""
    text = _environment().get_template(template).render(**context)
    # one blank line at most between kernels, exactly one newline at the end
    while "\n\n\n\n" in text:
        text = text.replace("\n\n\n\n", "\n\n\n")
    return text.rstrip("\n") + "\n"
