"""The HTTP and WebSocket API, one router per resource (each in its own module; api/router.py
gathers them for the app). Importing one module of it loads that module alone."""
