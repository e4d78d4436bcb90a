"""The WebSocket routes (keys, topic echo, a run's output, rosbridge) and what they share: a
lab's frame budget, a socket's life, relaying one socket to another, send-only channels."""
