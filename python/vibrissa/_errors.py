"""Exceptions of the vibrissa package; the message is the library's own."""


class Error(Exception):
    """Base class of every error the vibrissa library reports."""


class InputError(Error, ValueError):
    """A value outside its valid range, a malformed table or scene, an unknown name."""


class SolveError(Error, RuntimeError):
    """A solve that failed: no convergence, no contact, wrong branch, ..."""
