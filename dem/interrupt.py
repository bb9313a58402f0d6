"""SIGINT and SIGTERM.

Inside a run (and while a restart is written) a signal only sets a flag: an exception raised in the middle
of a write (h5py, pickle) would leave a half-written frame or a temporary file, and under MPI one rank
leaving a collective alone would hang the others. The run loop reads the flag once per step, folded into
a reduction it makes anyway (`Update.check_step`), so every rank stops at the end of the same step.
Anywhere else a signal raises `Interrupted` at once. Exit status 128 + signal number (130, 143), as a
shell reports a process killed by it.

The `dem` command takes the signals in a thread of its own (`Signals.install`): Python runs a handler only
between bytecodes of the main thread, so a signal sent while a kernel or a numpy call is busy would wait
for it. The thread passes the first signal to the main thread (as if it had arrived there) and says so on
the screen; a second one before the first was acted on ends the process at once (as Ctrl-C twice does in
LAMMPS): the outputs written so far are whole (atomic files, flushed lines), the step in progress is lost.
"""
import _thread
import contextlib
import os
import signal
import sys
import threading

SIGNALS = (signal.SIGINT, signal.SIGTERM)


class Interrupted(KeyboardInterrupt):
    """A SIGINT or SIGTERM stopped the script (a KeyboardInterrupt, so that plain Python code treats it as
    Ctrl-C). `step`: the step at which a run stopped (None outside a run); `text`: what was written."""

    def __init__(self, signum, text=None, step=None):
        self.signum = int(signum)
        self.step = step
        self.text = text or f"interrupted by {signal_name(signum)}"
        super().__init__(self.text)

    @property
    def exit_code(self):
        return 128 + self.signum


def signal_name(signum):
    try:
        return signal.Signals(signum).name
    except ValueError:
        return f"signal {signum}"


class Signals:
    """The process's pending signal. `pending`: the first signal number not yet acted on (0: none);
    `depth` > 0 while the signal must wait (`deferred`)."""

    def __init__(self):
        self.pending = 0
        self.depth = 0
        self.installed = False     # handlers set for the whole process (the `dem` command)
        self.delivered = 0         # signals the thread passed on that the main thread has not acted on

    def handler(self, signum, frame):
        if not self.pending:
            self.pending = signum
        if self.depth == 0:
            self.raise_pending()

    def raise_pending(self):
        signum, self.pending = self.pending, 0
        if signum:
            self.delivered = 0
            raise Interrupted(signum)

    def take(self):
        """The pending signal (0: none), now acted on."""
        signum, self.pending = self.pending, 0
        self.delivered = 0
        return signum

    def install(self):
        """The `dem` command: every SIGINT / SIGTERM of the process goes to a thread waiting for them
        (blocked in the others), which passes them to the handler in the main thread."""
        for s in SIGNALS:
            signal.signal(s, self.handler)
        if sys.version_info >= (3, 10):    # interrupt_main(signum): 3.10; before, the handler alone (the
            signal.pthread_sigmask(signal.SIG_BLOCK, SIGNALS)      # first signal waits for the step)
            threading.Thread(target=self._wait, name="dem-signals", daemon=True).start()
        self.installed = True

    def _wait(self):
        while True:
            signum = signal.sigwait(SIGNALS)
            name = signal_name(signum)
            if self.delivered:
                os.write(2, f"\nINTERRUPTED: a second {name}: stopped at once, in the middle of a step; "
                            "the files written before it are whole\n".encode())
                os._exit(128 + signum)
            self.delivered = signum
            os.write(2, f"\n{name}: stopping at the end of this step ({name} again: at once)\n".encode())
            _thread.interrupt_main(signum)

    @contextlib.contextmanager
    def deferred(self):
        """Signals wait (set `pending`) until the block ends; then a pending one raises Interrupted. A
        library caller (no `install`) gets the handlers for the block only, in the main thread."""
        own = not self.installed and self.depth == 0 and threading.current_thread() is threading.main_thread()
        previous = {s: signal.signal(s, self.handler) for s in SIGNALS} if own else {}
        self.depth += 1
        try:
            yield self
        finally:
            self.depth -= 1
            for s, h in previous.items():
                signal.signal(s, h)
        if self.depth == 0:
            self.raise_pending()


SIGNAL_STATE = Signals()
