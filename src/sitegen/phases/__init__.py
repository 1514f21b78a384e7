"""The build's phases: each takes the book (pages and one record per scene) and the run, and returns the book."""
