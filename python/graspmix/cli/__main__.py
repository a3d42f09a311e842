"""python -m graspmix.cli ..."""

import sys

from .main import main

sys.exit(main())
