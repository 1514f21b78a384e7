"""The site: templates, static assets (one script, one stylesheet, a math font) and the writer."""
