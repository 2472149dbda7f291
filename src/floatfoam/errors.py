"""User-facing errors: one line, exit code 2."""


class InputError(ValueError):
    """Bad input from the user (case file, --set, command line).

    The message is one line naming the parameter, its value and what would be valid.
    The CLI prints it without a traceback and exits with code 2.
    """
