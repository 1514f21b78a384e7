"""The reader's checks (tests/reader_checks.py) in Firefox ESR: Debian's Firefox ESR through puppeteer-core
(WebDriver BiDi)."""

import pytest
from reader_checks import *  # noqa: F403 (its fixtures and tests, collected here in their order)

pytestmark = pytest.mark.browser

ENGINE = "firefox"
