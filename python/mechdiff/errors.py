"""The exceptions of mechdiff: one class per kind of failure, all under `MechdiffError`.

Every exception carries the message of the Rust library word for word (``file:line:column``
for an error in the file, the drive position in the scene's units for one found by solving,
and what to do about it), and its parts as attributes:

- ``kind``: the Rust variant (``"Unassemblable"``, ``"Syntax"``, ...);
- ``file``, ``line``, ``column``: where in the scene file (``None`` where it does not apply);
- ``position``: the drive position with its unit, for a failure found by solving;
- ``settings``: the parameters as moved, for a run of a study or a variant.

The tree (a group, then the kinds with a class of their own)::

    MechdiffError
    ├── SceneFileError (OSError)          the file cannot be read
    │   └── ReadError, TooLargeError, NotRegularFileError, OutsideSceneFolderError,
    │       NotUtf8Error
    ├── SceneSyntaxError (ValueError)     not TOML, or a key or value the format does not know
    ├── InvalidSceneError (ValueError)    an inconsistency in the scene (unknown point, ...)
    │   └── UnknownPointError, UnknownNameError, DuplicatePointError,
    │       NonPositiveLengthError, OutOfRangeError, SceneImportError, UnconstructibleError
    ├── SettingError (ValueError)         a parameter setting that names no parameter, ...
    ├── ArgumentError (ValueError)        an argument of the Python API (shape, name)
    ├── LimitError (ValueError)           a count over its documented limit
    ├── FormulaError (ValueError)         a formula of `derive` that cannot be read or evaluated
    ├── ModelError                        mobility, redundancy
    ├── EvaluatorError                    the evaluator asked for cannot evaluate the scene
    ├── StudyError                        a sensitivity or tolerance study cannot be made
    ├── AccuracyError                     an accuracy report that cannot be measured
    └── MotionError                       found by solving a drive position
        ├── UnassemblableError, BlockedError, ChangePointError, SingularError,
        ├── BranchFlipError, NotReachedError, SelfLockingError, MoveTooLongError,
        ├── MachineMotionError (the machine's motion in time)
        └── NotFiniteError (also ArithmeticError)

A Ctrl-C during a run interrupts it with ``KeyboardInterrupt`` (the run looks for it every
1024 drive positions).
"""

from __future__ import annotations

from typing import Optional

__all__ = [
    "MechdiffError",
    "SceneFileError",
    "SceneSyntaxError",
    "InvalidSceneError",
    "SettingError",
    "ArgumentError",
    "LimitError",
    "ModelError",
    "EvaluatorError",
    "StudyError",
    "MotionError",
    "UnassemblableError",
    "BlockedError",
    "ChangePointError",
    "SingularError",
    "BranchFlipError",
    "NotReachedError",
    "SelfLockingError",
    "MoveTooLongError",
    "NotFiniteError",
]


class MechdiffError(Exception):
    """Any failure of mechdiff; the message says what is wrong, where, and what to do."""

    kind: Optional[str] = None
    file: Optional[str] = None
    line: Optional[int] = None
    column: Optional[int] = None
    position: Optional[str] = None
    settings: Optional[str] = None


class SceneFileError(MechdiffError, OSError):
    """The scene file cannot be read (missing, too large, not UTF-8, not a regular file)."""


class SceneSyntaxError(MechdiffError, ValueError):
    """The file is not TOML, or a key, type or value is not one the scene format knows."""


class InvalidSceneError(MechdiffError, ValueError):
    """An inconsistency in the scene: an unknown name, a length that is not positive, a
    number out of range, a point that cannot be constructed, a field missing."""


class SettingError(MechdiffError, ValueError):
    """A parameter setting that names no parameter of the scene or cannot be evaluated."""


class ArgumentError(MechdiffError, ValueError):
    """An argument of the Python API that does not fit (shape, column name, option)."""


class LimitError(MechdiffError, ValueError):
    """A count over its documented limit, refused before any work starts."""


class ModelError(MechdiffError):
    """The mechanism as a whole is rejected (mobility, redundancy)."""


class EvaluatorError(MechdiffError):
    """The evaluator asked for cannot evaluate this scene."""


class StudyError(MechdiffError):
    """A sensitivity or tolerance study that cannot give a right answer for this scene."""


class MotionError(MechdiffError):
    """A failure that only solving the drive positions finds; ``position`` says where."""


class UnassemblableError(MotionError):
    """The mechanism cannot be assembled at a drive position."""


class BlockedError(MotionError):
    """A loop stops closing between two drive positions (a limit position between them)."""


class ChangePointError(MotionError):
    """A loop reaches a change point (bifurcation) in the sweep."""


class SingularError(MotionError):
    """A singular position (toggle): the drive cannot move the mechanism there."""


class BranchFlipError(MotionError):
    """The solver would change assembly branch between two drive positions."""


class NotReachedError(MotionError):
    """No drive position gives the value of ``[sweep] of`` asked for."""


class SelfLockingError(MotionError):
    """No friction forces consistent with the motion: the mechanism locks itself."""


class MoveTooLongError(MotionError):
    """The motion between two drive positions could not be proven in the steps allowed."""


class NotFiniteError(MotionError, ArithmeticError):
    """A result left the range of f64 (overflow, or a singular position)."""


class FormulaError(MechdiffError, ValueError):
    """A formula that cannot be read or differentiated (``mechdiff.derive``, ``codegen``):
    the message names the place in the formula."""


# One class per kind the library distinguishes, under the class of its group: catch the
# group (``InvalidSceneError``) or the kind (``UnknownPointError``).


class ReadError(SceneFileError):
    """The file cannot be read (missing, no permission)."""


class TooLargeError(SceneFileError):
    """The file is larger than a scene may be."""


class NotRegularFileError(SceneFileError):
    """The path is a directory or a device, not a file."""


class OutsideSceneFolderError(SceneFileError):
    """A file the scene names lies outside the scene's folder."""


class NotUtf8Error(SceneFileError):
    """The file is not UTF-8 text (the message gives the line and column)."""


class UnknownPointError(InvalidSceneError):
    """A point name that the scene does not define (the message lists the points)."""


class UnknownNameError(InvalidSceneError):
    """A link, joint, output or other name that the scene does not define."""


class DuplicatePointError(InvalidSceneError):
    """A point defined twice."""


class NonPositiveLengthError(InvalidSceneError):
    """A length, radius or mass that must be positive and is not."""


class OutOfRangeError(InvalidSceneError):
    """A number outside the range its field allows."""


class SceneImportError(InvalidSceneError):
    """A geometry file the scene imports cannot be used."""


class UnconstructibleError(InvalidSceneError):
    """A point given by lengths that cannot be constructed (the circles do not meet)."""


class MachineMotionError(MotionError):
    """The motion of the machine in time (start-up, steady state) cannot be computed."""


class AccuracyError(MechdiffError):
    """An accuracy report that cannot be measured (a method failed, no reference)."""


#: The class of each kind (the Rust variant's name) that has its own.
_CLASS_OF_KIND = {
    "Read": ReadError,
    "TooLarge": TooLargeError,
    "NotRegularFile": NotRegularFileError,
    "OutsideSceneFolder": OutsideSceneFolderError,
    "NotUtf8": NotUtf8Error,
    "UnknownPoint": UnknownPointError,
    "UnknownName": UnknownNameError,
    "DuplicatePoint": DuplicatePointError,
    "NonPositiveLength": NonPositiveLengthError,
    "OutOfRange": OutOfRangeError,
    "Import": SceneImportError,
    "Unconstructible": UnconstructibleError,
    "Motion": MachineMotionError,
    "Method": AccuracyError,
    "MethodNotFinite": AccuracyError,
    "Reference": AccuracyError,
}


def class_for(kind: str, group: str) -> type:
    """The exception class of an error of ``kind`` (the Rust variant), whose group class is
    named ``group``: the kind's own class where it has one, else the group's (used by the
    Rust extension)."""
    own = _CLASS_OF_KIND.get(kind)
    if own is not None and issubclass(own, globals()[group]):
        return own
    return globals()[group]


__all__ += [
    "FormulaError",
    "ReadError",
    "TooLargeError",
    "NotRegularFileError",
    "OutsideSceneFolderError",
    "NotUtf8Error",
    "UnknownPointError",
    "UnknownNameError",
    "DuplicatePointError",
    "NonPositiveLengthError",
    "OutOfRangeError",
    "SceneImportError",
    "UnconstructibleError",
    "MachineMotionError",
    "AccuracyError",
]
