"""The reader's checks (tests/reader_checks.py) in Chromium: Debian's Chromium through Playwright."""

import pytest
from reader_checks import *  # noqa: F403 (its fixtures and tests, collected here in their order)

pytestmark = pytest.mark.browser

ENGINE = "chromium"
