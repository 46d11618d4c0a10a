"""Problem JSON text and files: compact number arrays, atomic writes."""
import base64
import json
import os
import re
import tempfile

# An innermost array of numbers, spread over lines by json.dumps(indent=...).
_NUMBER_ARRAY = re.compile(r"\[\s*(-?[0-9][-+0-9.eE]*(?:\s*,\s*-?[0-9][-+0-9.eE]*)*)\s*\]")


def dumps(problem: dict) -> str:
    """JSON text: indented objects, each innermost number array on one line.

    NaN and infinities are refused (``allow_nan=False``): the problem format
    rejects them, and the scene check names the field first.
    """
    text = json.dumps(problem, indent=1, allow_nan=False)
    return _NUMBER_ARRAY.sub(lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]", text) + "\n"


def write_atomic(path: str, text) -> None:
    """Write ``text`` (str, as UTF-8, or bytes) to ``path`` through a temporary file in the same folder and a rename.

    A reader (or a crash half-way) never sees a half-written problem file; the
    previous file stays in place until the new one is complete.
    """
    if isinstance(text, (bytes, bytearray)):
        data = bytes(text)
    elif isinstance(text, str):
        data = text.encode("utf-8")
    else:
        raise TypeError("write_atomic: expected str or bytes, got %s" % type(text).__name__)
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".", suffix=".tmp", dir=folder)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)  # mkstemp makes 0600; a normal file follows the umask
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


# A binary export (convergence.png) kept in a text property of the .blend.
_BINARY_PREFIX = "base64:"


def file_to_text(data: bytes) -> str:
    """An exported file as text for a Blender string property: UTF-8 as it is, anything else base64 with a prefix."""
    try:
        text = data.decode("utf-8")
        if not text.startswith(_BINARY_PREFIX):
            return text
    except UnicodeDecodeError:
        pass
    return _BINARY_PREFIX + base64.b64encode(data).decode("ascii")


def text_to_file(text: str):
    """The inverse of ``file_to_text``: bytes for a base64-stored file, else the text itself."""
    if text.startswith(_BINARY_PREFIX):
        return base64.b64decode(text[len(_BINARY_PREFIX):])
    return text


def read(path: str) -> dict:
    """The JSON object in ``path``; raises ValueError with the file name on bad JSON."""
    with open(path, "r", encoding="utf-8") as f:
        try:
            return json.load(f)
        except json.JSONDecodeError as e:
            raise ValueError("%s: is not valid JSON (%s)" % (path, e)) from None
