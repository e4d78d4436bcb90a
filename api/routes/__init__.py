"""The REST routes, one module per resource, and the page's own (viser's client, /tools)."""
