"""Accuracy and cost: declared numerical settings, in-build reference checks, and the report page."""
