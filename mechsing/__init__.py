"""mechsing: find and classify the singularities of mechanisms with Lie groups.

Conventions (stated once, used everywhere; the README says them too):

* A twist is a 6-vector ``(omega, v)``: angular part first, then the velocity
  of the body point at the ground origin.  A wrench is ``(f, m)``: force, then
  moment about the ground origin.  Slices :data:`mechsing.lie.ANGULAR` and
  :data:`mechsing.lie.LINEAR` are the only place the ordering is written.
* The Lie bracket is the commutator of 4x4 matrices; ``Ad(R, p) = [[R, 0],
  [p^ R, R]]`` moves twists and (f, m) wrenches alike.
* A displacement ``g = (R, p)`` acts on points as ``x -> R x + p`` and is
  stored as a homogeneous 4x4 matrix.  A joint with ``between: [a, b]`` and
  value q sets ``g_b = g_a . exp(sum q_i e_i)`` (spatial product of
  exponentials, basis screws at the reference configuration in the ground frame).
* Lengths in metres, angles in radians, pitch in metres per radian.

API: :func:`load` (a mechanism file of any format: YAML, JSON, a DH table, URDF, MJCF), :func:`analyze` (a result whose
``to_json()`` is the JSON contract), :func:`scan` (batched float verdicts of
an open chain over many configurations), :func:`sweep` (where the
singularities are along a path or over a grid of joint values or output poses:
a ``SweepResult`` with the measures at every sample, the located and classified
singularities and a grid's loci), :func:`condition` (singularity conditions as
factored formulas in the joint or pose variables), :func:`report` (a design-review
document, HTML or Markdown), :func:`mechsing.analysis.solve.solve` (one configuration
closed, every joint value to the precision's digits), :func:`modes` (every assembly mode
of a configuration, certified and classified: :mod:`mechsing.assembly`), :func:`dynamics`
(inverse and forward dynamics of a configuration: efforts, accelerations, the mass matrix;
:mod:`mechsing.kinetics`), :mod:`mechsing.lie`,
:func:`mechsing.subgroups.identify`.
"""

#: the version of mechsing (the package's version in pyproject.toml)
__version__ = "0.1.0"

import importlib

#: the public API: functions (loaded on first use, so ``mechsing --version`` stays fast)
#: and the layers a script uses directly
_FUNCTIONS = {
    "analyze": ("mechsing.analysis", "analyze"),
    "condition": ("mechsing.conditions", "condition"),
    "dynamics": ("mechsing.kinetics", "dynamics"),
    "load": ("mechsing.reader", "read_mechanism"),  # any format: YAML, JSON, DH, URDF, MJCF
    "modes": ("mechsing.assembly", "modes"),
    "report": ("mechsing.reports", "report"),
    "scan": ("mechsing.sweeps.scan", "scan"),
    "sweep": ("mechsing.sweeps", "sweep"),
    "cusps": ("mechsing.assembly.cusps", "cusps"),
    # the frozen closed configuration analyze, modes and sweep hand on
    "ClosedValue": ("mechsing.kinematics.closed", "ClosedValue"),
}
_MODULES = ("errors", "lie", "numeric", "subgroups", "model", "kinematics", "screws", "singularity")

__all__ = ["__version__", *_FUNCTIONS, *_MODULES]


def __getattr__(name: str):  # lazy: importing mechsing loads no numerics
    if name in _FUNCTIONS:
        module, attr = _FUNCTIONS[name]
        return getattr(importlib.import_module(module), attr)
    if name in _MODULES:
        return importlib.import_module(f"mechsing.{name}")
    raise AttributeError(f"module 'mechsing' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *__all__})
