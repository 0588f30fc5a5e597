"""Library errors as Blender shows them (no bpy here)."""


def describe(error):
    """One line for a report: a ShaftsError with its location, else the
    exception's type and message."""
    parts = []
    where = getattr(error, "file", None)
    if where:
        line, column = getattr(error, "line", 0), getattr(error, "column", 0)
        parts.append("%s:%d:%d:" % (where, line, column) if line else where + ":")
    key = getattr(error, "key", None)
    if key:
        parts.append(str(key) + ":")
    message = getattr(error, "message", None) or str(error) or type(error).__name__
    parts.append(message)
    if not hasattr(error, "status"):
        parts.insert(0, type(error).__name__ + ":")
    return " ".join(parts)


def is_cancelled(error):
    return getattr(error, "status", None) in ("cancelled", "SH_ERR_CANCELLED")
