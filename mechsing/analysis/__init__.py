"""The analysis of a mechanism at its configurations (the API behind ``mechsing analyze``).

>>> import mechsing
>>> result = mechsing.analyze("examples/fourbar.yaml")     # doctest: +SKIP
>>> result.to_json()["configurations"][1]["mobility"]       # doctest: +SKIP
{'grubler': -2, 'group': 1, 'instantaneous': 1, 'generic': 1, 'finite': 1}

Precision: ``auto`` decides in float and re-does a configuration at mp:50
when a rank is undecided there, or when float found it singular on a dropped
singular value far above float's own rounding
(:func:`mechsing.numeric.float_drop_is_real`: float's thresholds call it zero,
float's data say it is not); ``float``, ``mp:N`` and ``exact`` use one mode.

Exact mode works on each configuration within a time limit (``time_limit``, default
60 s): a configuration that sympy cannot finish in time is stopped wherever sympy is
(:mod:`mechsing.timelimit`) and gets an ``error`` entry that says what could not be
proved, like a configuration that does not close; the others are reported.
"""

from mechsing.analysis.results import AnalysisResult, ConfigurationResult
from mechsing.analysis.run import analyze, analyze_found

__all__ = ["AnalysisResult", "ConfigurationResult", "analyze", "analyze_found"]
