"""Base class of commands: `style` is the command word, the docstring its documentation, and calling the
instance with the argument strings runs it."""
from .args import Args


class Command:
    kind = "command"
    style = None
    usage = ""

    def __init__(self, sim):
        self.sim = sim

    def args(self, words):
        return Args(words, f"{self.style} {self.usage}".strip(), self.style)

    def __call__(self, words):
        raise NotImplementedError
