"""Exceptions of autobal. Every error of the library arrives as one of these; those about an
input name it in ``.field`` as the config spells it (``planar.m3``, ``dimensionless.delta_a``)
and say why in ``.reason``.

    AutobalError
    ├── InvalidParameter (also ValueError)   a value outside its range, an unknown key or path
    │   └── TooLarge                         a size beyond a limit (balls, grid points, file)
    ├── NoConvergence (also ArithmeticError) the eigenvalue iteration did not converge
    ├── SimulationError (also RuntimeError)  a run that could not go on (step size underflow,
    │                                        non-finite state, singular mass matrix)
    └── Interrupted                          a run stopped on request before its end

Ctrl-C during a long call raises the usual ``KeyboardInterrupt`` after the work has stopped.
"""

from __future__ import annotations

from typing import Any, Optional

__all__ = ["AutobalError", "InvalidParameter", "TooLarge", "NoConvergence", "SimulationError", "Interrupted"]


class AutobalError(Exception):
    """Base class of autobal's errors."""

    #: The input field the error is about, as the config spells it (``planar.m3``), if any.
    field: Optional[str] = None
    #: Why the value was rejected, if the error is about a field.
    reason: Optional[str] = None
    #: What was computed before the error, where something was (e.g. a run's summary).
    result: Any = None


class InvalidParameter(AutobalError, ValueError):
    """An input outside its physical or numerical range, an unknown key or parameter path."""


class TooLarge(InvalidParameter):
    """An input or requested output beyond a resource limit."""


class NoConvergence(AutobalError, ArithmeticError):
    """An iterative solver (the eigenvalue QR iteration) did not converge."""


class SimulationError(AutobalError, RuntimeError):
    """A simulation that stopped before its end on its own (its ``.result`` has the summary)."""


class Interrupted(AutobalError):
    """A run stopped on request before its end."""
