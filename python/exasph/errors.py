class ExasphFileError(Exception):
    """A file that is missing, unreadable or not what exasph writes (one line: file, problem)."""
