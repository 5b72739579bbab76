"""One path engine: following a mechanism's closed configurations along a path.

Every path mechsing follows goes through this package: the continuation of a named
configuration's closure (:mod:`mechsing.kinematics.continuation`), a sweep's paths and
grids (:mod:`mechsing.sweeps`) and the effort limits located along them
(:mod:`mechsing.statics.along`).

* :mod:`.steps`: one step in the given coordinates (tangent predictor, damped Newton on
  the group, the assembly-mode jump check);
* :mod:`.problem`: a path's problem (the float model, the given coordinates, the tools
  that close);
* :mod:`.nodes`: a path's nodes (prediction from the tangent, the secant or the polynomial
  through the last nodes; one batched Newton, kept when the correction is small);
* :mod:`.segments`: the samples between nodes, many at a time;
* :mod:`.folds`: folds of the given values: landing on one, the samples near one
  (the square-root law), locating one along the curve, and turning at one (leaving it
  on the other assembly mode);
* :mod:`.arc`: pseudo-arclength continuation of a path's curve through its folds;
* :mod:`.follow`: a path followed through its samples (and several in lockstep), its
  record :class:`~.trace.PathTrace` (:mod:`.trace`);
* :mod:`.crossing`: where a scalar read along a path crosses a value.

The package's modules are imported by name (this file imports none: continuation, which
the closure of every configuration loads, needs only its steps and folds).
"""
