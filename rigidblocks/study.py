"""``import rigidblocks.study`` and ``from rigidblocks import study``: the studies
package (:mod:`rigidblocks.studies`) under its short name, the same module object."""

import sys

from . import studies

sys.modules[__name__] = studies
