"""The package's exceptions and warning categories, which every layer may raise or issue.

Every warning the package issues is an :class:`AtcmWarning`, of one of the categories below,
each of which says what kind of change the message asks for.  Turn them into errors, or
silence one kind, with the standard filters::

    import warnings
    from exudyn_atcm.errors import AtcmWarning, AccuracyWarning

    warnings.simplefilter("error", AtcmWarning)        # every warning of the package
    warnings.simplefilter("ignore", AccuracyWarning)   # only the accuracy notes

or on the command line ``python -W error::exudyn_atcm.errors.AtcmWarning``.  The categories
other than :class:`AtcmDeprecationWarning` are also ``RuntimeWarning`` subclasses, so filters
written for ``RuntimeWarning`` keep working; :class:`AtcmDeprecationWarning` is a
``DeprecationWarning`` (hidden by default outside ``__main__``, shown by test runners).
"""

from __future__ import annotations

__all__ = [
    "annotate",
    "SolverError",
    "WriteError",
    "AtcmWarning",
    "InputRangeWarning",
    "AccuracyWarning",
    "StabilityWarning",
    "OutOfReachWarning",
    "RunCostWarning",
    "SetupWarning",
    "SuspectFileWarning",
    "AtcmDeprecationWarning",
]


def annotate(exc: BaseException, note: str) -> BaseException:
    """Add ``note`` to ``exc`` (``BaseException.add_note``, shown under the message) and return it.

    The package names the context of an error raised by the user's own code (the voltage program,
    the drive and the simulated time) this way, so that the error keeps its type and message.
    A note already there is not added twice; before Python 3.11 (no notes) nothing is added.
    """
    add_note = getattr(exc, "add_note", None)
    if add_note is not None and note not in getattr(exc, "__notes__", ()):
        add_note(note)
    return exc


class SolverError(RuntimeError):
    """The multibody solver failed; the message says where, what was tried and what to change."""


class WriteError(OSError):
    """A file or directory the user asked for could not be written; the message names the path and why.

    An ``OSError`` because the operating system refused the write (no permission, disk full, a name
    too long, a path that is a directory or empty): code that guards its writes with
    ``except OSError`` (what ``open`` raises for the same causes) catches it too.  ``errno`` is the
    failed call's error number when there was one, and ``filename`` the path as given.
    """

    def __str__(self) -> str:  # the message as written, not OSError's "[Errno n] strerror: filename"
        return str(self.args[0]) if len(self.args) == 1 else super().__str__()


class AtcmWarning(UserWarning):
    """Base class of every warning issued by ``exudyn_atcm``."""


class InputRangeWarning(AtcmWarning, RuntimeWarning):
    """A value given is outside the rated or plausible range (a voltage beyond the MFC rating, a
    layer thickness of 2 m, a program whose times look like milliseconds): most likely a unit
    or typing mistake.  The message quotes the value as given and the range."""


class AccuracyWarning(AtcmWarning, RuntimeWarning):
    """The answer is computed, but only approximately or with a qualification the message
    states: a step or record interval too coarse for the voltage program or the lowest mode,
    a step adjusted to divide ``t_end``, too few cells, the ritz model's linearisation, a
    linearisation about a state that is not an equilibrium (or an unstable one), a fitted
    model used outside the data it was fitted to.  The message says what to change."""


class StabilityWarning(AccuracyWarning):
    """A static equilibrium was found, but it is unstable or at a stability limit (critical): the
    lowest eigenvalue of the constrained tangent stiffness is negative or near zero (a column
    above its buckling load held straight, a mechanism at a snap-through point).  A real
    mechanism would not rest there, or its pose depends on imperfections the model does not
    hold.  The message gives the load factor or sweep point and what to do (add an imperfection,
    reduce the loads).  An :class:`AccuracyWarning`, so filters for those catch it; filter it on
    its own to reject unstable designs in a study (``warnings.simplefilter("error",
    StabilityWarning)``)."""


class OutOfReachWarning(AtcmWarning, RuntimeWarning):
    """A wanted output cannot be reached within the input range: an inverse or feedforward
    clipped it, or a controller sat at its output limits.  The message says by how much."""


class RunCostWarning(AtcmWarning, RuntimeWarning):
    """A run or fit is predicted to take long; the message gives the estimate and how to
    make it quicker."""


class SetupWarning(AtcmWarning, RuntimeWarning):
    """Part of what was set up is not used as given: a load on a body welded to the ground, a
    step hook replaced by another, a case name found in several files, a stored run record
    that cannot be used, a model family that could not be fitted."""


class SuspectFileWarning(AtcmWarning, RuntimeWarning):
    """A data file was read, but part of it looks wrong (possibly cut off, a kV column labelled V, ...).

    The message names the file, the line or column and what to check.  Turn it into an error
    with ``warnings.simplefilter("error", SuspectFileWarning)`` in scripts that must not go on.
    """


class AtcmDeprecationWarning(AtcmWarning, DeprecationWarning):
    """A name, module path or way of calling that goes away in the next release; the message
    names its replacement."""
