"""The shapes the API exchanges, declared once in Python: request and response models, the
error responses, the OpenAPI document, and their TypeScript for the page."""
