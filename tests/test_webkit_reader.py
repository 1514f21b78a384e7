"""The reader's checks (tests/reader_checks.py) in WebKitGTK: Debian's WebKitGTK (MiniBrowser) through
WebKitWebDriver and selenium, in a virtual display."""

import pytest
from reader_checks import *  # noqa: F403 (its fixtures and tests, collected here in their order)

pytestmark = pytest.mark.browser

ENGINE = "webkit"
