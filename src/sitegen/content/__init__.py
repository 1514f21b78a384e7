"""Reading the author's sources: pages, front matter, scene blocks, Markdown and math."""
