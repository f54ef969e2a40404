"""Displayed equations are simplified, in Chromium against the served app (issue 29, item 11).

Lesson 9.3 derives the heavy top and the rolling disk by every formulation. The heavy top's Routh equation for θ was
17 terms, 3 859 characters of LaTeX ((I_a β_φ − I_a β_ψ cos θ)… over I_t² sin⁴θ, again and again); it is now one
fraction over I_t sin³θ. The rolling disk's Kane equations kept r² sin²ψ + r² cos²ψ in their coefficients. The
equations' TeX is read from KaTeX's own annotation of each rendered equation.
"""

from __future__ import annotations

import re

import pytest

from tests.browser.conftest import keeping_screenshots, open_lesson, screenshot

pytestmark = pytest.mark.browser
LESSON = "/lessons/9-3-gibbs-appell-and-kane"
#: A cold derivation cache derives both systems by every formulation (and simplifies what is shown): allow for it.
DERIVED_WITHIN_MS = 240_000


def equations_tex(page, system: str, formulation: str) -> list[str]:
    column = f'#derivations [data-system="{system}"] .formulation[data-formulation="{formulation}"]'
    page.wait_for_selector(f'{column}[data-ready="true"]', timeout=DERIVED_WITHIN_MS)
    return page.locator(f"{column} .equations annotation").all_text_contents()


def test_the_heavy_tops_routh_and_the_rolling_disks_kane_equations_are_simplified(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, LESSON, viewer=False, viewport=(1500, 1000))
    routh = equations_tex(page, "heavy-top", "routh")
    assert len(routh) == 3, routh
    theta = routh[0]
    assert theta.startswith("I_{t} \\ddot{\\theta} =") and len(theta) < 400, (len(theta), theta[:200])
    assert "I_{a} \\beta_{\\phi} - I_{a} \\beta_{\\psi}" not in theta  # the unsimplified form's repeated factor
    kane = equations_tex(page, "rolling-disk", "kane")
    for equation in kane:
        for angle in ("psi", "phi", "theta"):
            pair = [re.search(rf"\\{trig}\^{{2}}{{\\left\(\\{angle} \\right\)}}", equation) for trig in ("sin", "cos")]
            assert not all(pair), (angle, equation)  # no sin²x + cos²x left in one equation
    assert page.locator("#derivations .katex-error").count() == 0
    column = page.locator('#derivations [data-system="heavy-top"] .formulation[data-formulation="routh"]')
    if keeping_screenshots():  # the picture for the docs: the Routh column alone, as wide as its widest equation
        column.evaluate(
            "(el) => { el.querySelector('details').open = true;"
            " for (const other of el.parentElement.children) if (other !== el) other.style.display = 'none';"
            " el.parentElement.style.display = 'block';"
            " const widest = Math.max(...[...el.querySelectorAll('.katex-display')].map((e) => e.scrollWidth));"
            " el.style.width = `${widest + 40}px`; }"
        )
    column.scroll_into_view_if_needed()
    screenshot(column, shots / "heavy-top-routh-equations.png")
    assert not errors, errors
    context.close()
