"""Errors that stop a run with one line and no traceback: the run did what the deck asked."""


class RunStopped(Exception):
    """The run stops for a reason the user chose or must act on (e.g. particles leaving the
    domain with <particles_leaving_domain>error); the CLI prints one line, the last checkpoint stays."""
