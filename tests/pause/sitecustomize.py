"""Loaded by every Python process started with this folder on PYTHONPATH (the tests'
``conftest.paused_write``): a result file's write pauses :data:`PAUSE` seconds after its
temporary file is made, with the write's signals deferred (a write of the tiny workflow
lasts milliseconds, too short to be hit by a signal on purpose).  It lives in tests/:
production code holds no hook."""

import os
import tempfile
import time

#: Seconds to pause (set by paused_write; unset: this module does nothing).
PAUSE = "TENNIS_STROKE_TEST_WRITE_PAUSE"

if os.environ.get(PAUSE):
    _mkstemp, _made = tempfile.mkstemp, set()

    def _paused_mkstemp(*args, **kwargs):
        made = _mkstemp(*args, **kwargs)
        key = (kwargs.get("prefix"), str(kwargs.get("dir")))
        if kwargs.get("suffix") == ".tmp" and key in _made:
            time.sleep(float(os.environ[PAUSE]))  # the write's own file, not the probe
        _made.add(key)
        return made

    tempfile.mkstemp = _paused_mkstemp
