"""The folder a report goes to (`poundbench report --out DIR`), under the rule every output
of poundbench obeys (output/output_files.hpp): no file it writes may be one of its inputs, and
none is left half-written.

The report is written into a new folder of its own (Staging), then moved into DIR: a DIR that
does not exist yet is that folder renamed, so that it appears whole or not at all; into one
that exists (which may hold the study itself: `--out .`) each file is moved in turn, README.md
last, once every one of them was checked against the inputs. A report that fails, on a bad
input or a bug, leaves DIR as it was and removes its own folder. The new folder is made beside
DIR, or inside it when DIR exists (its parent may not be writable: `--out .` in a home), so
that a move is a rename on one file system. Rejected: checking the figures' names before they
are drawn (they come from the families and panels, known only as the sections run), and
writing into DIR directly (a failure halfway left a folder of some figures and no README)."""

import errno
import os
import shutil
import tempfile

# What the report writes into DIR, and last of all README.md, which shows the rest.
FILES = ("report.html", "README.md")
FIGURES = "figures"


class OutputError(Exception):
    """--out cannot take the report: one line naming the file and why."""


def _clip(path, most=120):
    return path if len(path) <= most else path[:most] + "..."


def _same_file(a, b):
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def check_target(out, name, inputs):
    """OutputError when the report's file `name` (relative to out) cannot be written there:
    a folder is in its place, or an input is that file (inputs: (flag, path) pairs)."""
    target = os.path.join(out, name)
    for flag, path in inputs:
        if path and _same_file(path, target):
            raise OutputError(f"{flag}: {_clip(path)}: would be overwritten by --out's {_clip(name)} (an output "
                              "must not be an input)")
    if os.path.isdir(target):
        raise OutputError(f"--out: {_clip(target)}: is a folder, where the report writes a file")


class Staging:
    """The report's own new folder (`path`), and what moves it into out (publish) or removes
    it (remove). Checks out and the report's fixed names against the inputs first, so that a
    clash is refused before anything is drawn."""

    def __init__(self, out, inputs):
        self.out, self.inputs = out, inputs
        self.path = None
        self._made = []  # the folders above out this made (removed again if the report fails)
        if not out:
            raise OutputError("--out: an empty folder name")
        if os.path.exists(out) and not os.path.isdir(out):
            raise OutputError(f"--out: {_clip(out)}: not a directory")
        if os.path.isdir(out):
            for name in FILES:
                check_target(out, name, inputs)
            figures = os.path.join(out, FIGURES)
            if os.path.exists(figures) and not os.path.isdir(figures):
                raise OutputError(f"--out: {_clip(figures)}: not a directory (the report's figures go there)")
        try:
            self.path = self._make()
        except OSError as e:
            self.remove()
            raise OutputError(f"--out: {_clip(out)}: cannot be created ({e.strerror})") from None

    def _make(self):
        if os.path.isdir(self.out):
            return tempfile.mkdtemp(prefix=".report-", suffix=".tmp", dir=self.out)
        parent = os.path.dirname(os.path.abspath(self.out))
        missing = []
        while not os.path.isdir(parent):
            missing.append(parent)
            parent = os.path.dirname(parent)
        for folder in reversed(missing):
            os.mkdir(folder)
            self._made.append(folder)
        path = tempfile.mkdtemp(prefix=f".{os.path.basename(os.path.abspath(self.out))[:60]}-", suffix=".tmp",
                                dir=os.path.dirname(os.path.abspath(self.out)))
        umask = os.umask(0)  # mkdtemp's folder is the owner's alone; DIR gets the usual permissions
        os.umask(umask)
        os.chmod(path, 0o777 & ~umask)
        return path

    def written(self):
        """The report's files, relative to its folder: the figures, then FILES."""
        figures = os.path.join(self.path, FIGURES)
        names = sorted(os.listdir(figures)) if os.path.isdir(figures) else []
        return [os.path.join(FIGURES, n) for n in names] + [
            n for n in FILES if os.path.exists(os.path.join(self.path, n))]

    def publish(self):
        """Moves the report into out: the whole folder by one rename where out does not exist,
        else every file checked against the inputs, then each moved, README.md last."""
        if not os.path.exists(self.out):
            try:
                os.rename(self.path, self.out)
                self.path, self._made = None, []
                return
            except OSError as e:
                if e.errno not in (errno.EEXIST, errno.ENOTEMPTY):
                    raise
        names = self.written()
        for name in names:
            check_target(self.out, name, self.inputs)
        os.makedirs(os.path.join(self.out, FIGURES), exist_ok=True)
        for name in names:
            os.replace(os.path.join(self.path, name), os.path.join(self.out, name))
        self._made = []
        self.remove()

    def remove(self):
        """Removes the report's own folder (what is left of it) and the folders made for it."""
        if self.path:
            shutil.rmtree(self.path, ignore_errors=True)
            self.path = None
        for folder in reversed(self._made):
            try:
                os.rmdir(folder)
            except OSError:
                pass
        self._made = []
